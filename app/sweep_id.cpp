#include "sweep_id.hpp"

#include <openssl/evp.h>

#include <array>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

namespace floornav {

SweepHasher::SweepHasher() : ctx_(EVP_MD_CTX_new()) {
  if (ctx_ == nullptr ||
      EVP_DigestInit_ex(static_cast<EVP_MD_CTX*>(ctx_), EVP_sha256(), nullptr) != 1)
    throw std::runtime_error("OpenSSL: cannot start SHA-256");
  add("format", "floornav-sweep-1");
}

SweepHasher::~SweepHasher() {
  EVP_MD_CTX_free(static_cast<EVP_MD_CTX*>(ctx_));
}

void SweepHasher::update(std::string_view bytes) {
  if (EVP_DigestUpdate(static_cast<EVP_MD_CTX*>(ctx_), bytes.data(), bytes.size()) != 1)
    throw std::runtime_error("OpenSSL: SHA-256 update failed");
}

void SweepHasher::add(std::string_view label, std::string_view text) {
  update(fmt::format("{}:{}:{}:", label.size(), label, text.size()));
  update(text);
}

void SweepHasher::add_file(std::string_view label, const std::filesystem::path& path) {
  add(label, path.string());
  add_content(label, path);
}

void SweepHasher::add_content(std::string_view label, const std::filesystem::path& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  update(fmt::format("{}:{}:", label.size(), label));
  update(fmt::format("{}:", ec ? 0 : size));
  std::ifstream in(path, std::ios::binary);
  std::array<char, 1 << 16> buffer{};
  while (in) {
    in.read(buffer.data(), buffer.size());
    update(std::string_view(buffer.data(), static_cast<std::size_t>(in.gcount())));
  }
}

std::string SweepHasher::id() {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int length = 0;
  if (EVP_DigestFinal_ex(static_cast<EVP_MD_CTX*>(ctx_), digest.data(), &length) != 1)
    throw std::runtime_error("OpenSSL: SHA-256 failed");
  std::string out;
  for (unsigned int i = 0; i < 8 && i < length; ++i) out += fmt::format("{:02x}", digest[i]);
  return out;
}

}  // namespace floornav
