#pragma once
// The id of a sweep: a SHA-256 fingerprint (OpenSSL) of everything a batch's lines depend on, so
// that merge can tell the shards of one sweep from those of another. The same command on the same
// input files with the same floornav gives the same id on any machine, for any --jobs and any
// --shard.

#include <filesystem>
#include <string>
#include <string_view>

namespace floornav {

class SweepHasher {
 public:
  SweepHasher();
  ~SweepHasher();
  SweepHasher(const SweepHasher&) = delete;
  SweepHasher& operator=(const SweepHasher&) = delete;

  /// Adds a labelled piece of text (length-prefixed: no two inputs run together).
  void add(std::string_view label, std::string_view text);
  /// Adds a file's name as given and its whole content (read in pieces).
  void add_file(std::string_view label, const std::filesystem::path& path);
  /// Adds a file's whole content, not its name: for files a scenario names (a map, its image, a
  /// people_file), whose paths differ from machine to machine while the scenario's text, which
  /// names them, is hashed already.
  void add_content(std::string_view label, const std::filesystem::path& path);
  /// The first 16 hex digits of the SHA-256 (64 bits: enough to tell sweeps apart).
  std::string id();

 private:
  void update(std::string_view bytes);
  void* ctx_;  // EVP_MD_CTX
};

}  // namespace floornav
