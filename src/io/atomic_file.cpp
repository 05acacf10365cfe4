#include "floornav/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <string>
#include <system_error>

#include "floornav/core/input_error.hpp"
#include "floornav/core/output_error.hpp"

namespace floornav {

namespace {

std::atomic<unsigned long> g_temp_counter{0};

[[noreturn]] void throw_cannot_write(const std::filesystem::path& path, int error) {
  throw OutputError(path.string(), std::string("cannot write: ") + std::strerror(error));
}

/// A unique name in the target's directory, so that the final rename stays on one filesystem.
std::filesystem::path temp_path_for(const std::filesystem::path& path) {
  std::string name = path.string();
  name += ".tmp.";
  name += std::to_string(static_cast<long>(::getpid()));
  name += '.';
  name += std::to_string(g_temp_counter.fetch_add(1, std::memory_order_relaxed));
  return name;
}

/// Writes everything or returns the errno of the first failure (0 on success).
int write_all(int fd, std::string_view content) {
  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    if (n == 0) return ENOSPC;  // a write that makes no progress: treat as a full disk
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  return 0;
}

}  // namespace

void write_file_atomically(
    const std::filesystem::path& path,
    const std::function<void(const std::function<void(std::string_view)>& sink)>& produce) {
  const std::filesystem::path temp = temp_path_for(path);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) throw_cannot_write(path, errno);

  int error = 0;  // the first failure; later pieces are skipped
  try {
    produce([&](std::string_view piece) {
      if (error == 0) error = write_all(fd, piece);
    });
  } catch (...) {  // the producer failed: no half file is left, and the error is its own
    ::close(fd);
    std::error_code ignored;
    std::filesystem::remove(temp, ignored);
    throw;
  }
  if (::close(fd) != 0 && error == 0) error = errno;  // NFS and quotas report late, at close
  if (error == 0) {
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (!ec) return;
    error = ec.value();
  }
  std::error_code ignored;
  std::filesystem::remove(temp, ignored);
  throw_cannot_write(path, error);
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content) {
  write_file_atomically(path,
                        [&](const std::function<void(std::string_view)>& sink) { sink(content); });
}

void ensure_directory(const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    throw OutputError(dir.string(), "cannot write: cannot create the folder: " + ec.message());
  if (!std::filesystem::is_directory(dir, ec))
    throw OutputError(dir.string(), "cannot write: it exists and is not a folder");
}

OutputFolder::OutputFolder(std::filesystem::path dir, std::vector<std::string> owned)
    : dir_(dir.lexically_normal()), owned_(std::move(owned)) {
  if (dir_.has_filename() == false && dir_.has_parent_path()) dir_ = dir_.parent_path();
  if (dir_.empty() || dir_ == "." || dir_ == "..")
    throw InputError(dir.string(), "", "cannot write outputs there: name a folder below it");
  std::error_code ec;
  if (std::filesystem::exists(dir_, ec) && !std::filesystem::is_directory(dir_, ec))
    throw OutputError(dir_.string(), "cannot write: it exists and is not a folder");
}

OutputFolder::~OutputFolder() {
  std::error_code ignored;
  if (!staging_.empty()) std::filesystem::remove_all(staging_, ignored);
  if (committed_) return;
  // Folders this set created and left empty go too (remove() takes only empty folders).
  for (auto it = created_.rbegin(); it != created_.rend(); ++it)
    std::filesystem::remove(*it, ignored);
}

void OutputFolder::stage() {
  if (!staging_.empty()) return;
  // The folder and any missing parents, each remembered: a failure removes them again.
  std::vector<std::filesystem::path> missing;
  std::error_code ec;
  for (std::filesystem::path p = dir_; !p.empty() && !std::filesystem::exists(p, ec);
       p = p.parent_path()) {
    missing.push_back(p);
    if (!p.has_parent_path() || p.parent_path() == p) break;
  }
  for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
    if (!std::filesystem::create_directory(*it, ec) && ec)
      throw OutputError(it->string(), "cannot write: cannot create the folder: " + ec.message());
    created_.push_back(*it);
  }
  if (!std::filesystem::is_directory(dir_, ec))
    throw OutputError(dir_.string(), "cannot write: it exists and is not a folder");
  // Staged inside the folder itself (never in its parent, which may be read-only, another
  // filesystem, or not the user's): each file is renamed into place within one folder.
  std::string name = ".floornav-staging.";
  name += std::to_string(static_cast<long>(::getpid()));
  name += '.';
  name += std::to_string(g_temp_counter.fetch_add(1, std::memory_order_relaxed));
  const std::filesystem::path staging = dir_ / name;
  if (!std::filesystem::create_directory(staging, ec))
    throw OutputError(dir_.string(), "cannot write: cannot create a staging folder in it: " +
                                         (ec ? ec.message() : "it exists"));
  staging_ = staging;
}

void OutputFolder::write(const std::string& name, std::string_view content) {
  write(name, [&](const std::function<void(std::string_view)>& sink) { sink(content); });
}

void OutputFolder::write(
    const std::string& name,
    const std::function<void(const std::function<void(std::string_view)>& sink)>& produce) {
  std::filesystem::path staged;
  {
    const std::lock_guard lock(mutex_);
    stage();
    staged = staging_ / name;
  }
  try {
    write_file_atomically(staged, produce);
  } catch (const OutputError& e) {
    // Name the file where it was meant to go, not the staging folder.
    throw OutputError((dir_ / name).string(), e.detail);
  }
  const std::lock_guard lock(mutex_);
  names_.push_back(name);
}

void OutputFolder::commit() {
  if (committed_) return;
  stage();  // also for a set of no files: the folder exists afterwards
  std::error_code ec;
  for (const std::string& name : names_) {
    std::filesystem::rename(staging_ / name, dir_ / name, ec);
    if (ec) throw OutputError((dir_ / name).string(), "cannot write: " + ec.message());
  }
  committed_ = true;
  // What an earlier output of the same kind left and this one does not replace (its replay, its
  // crowd.csv) would sit beside the new files as if it belonged to them: removed.
  for (const std::string& name : owned_)
    if (std::find(names_.begin(), names_.end(), name) == names_.end())
      std::filesystem::remove(dir_ / name, ec);
  std::filesystem::remove_all(staging_, ec);
  staging_.clear();
}

std::string safe_file_name(std::string_view name) {
  std::string out;
  for (const char c : name.substr(0, 120)) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '-' || c == '_' || c == '.';
    out += ok ? c : '_';
  }
  while (!out.empty() && out.front() == '.') out.front() = '_';
  return out.empty() ? std::string("_") : out;
}

}  // namespace floornav
