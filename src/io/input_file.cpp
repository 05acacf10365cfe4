#include "input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <fmt/format.h>

#include "floornav/core/input_error.hpp"

namespace floornav::io_detail {

namespace {

/// The problem with a file whose status is `st`, or nullopt.
std::optional<std::string> status_problem(const struct stat& st, std::string_view what,
                                          std::uint64_t max_bytes) {
  const auto not_a = [&](std::string_view kind) {
    return fmt::format("is {}, not a {} file", kind, what);
  };
  if (S_ISDIR(st.st_mode)) return not_a("a directory");
  if (S_ISFIFO(st.st_mode)) return not_a("a FIFO (named pipe)");
  if (S_ISCHR(st.st_mode)) return not_a("a character device");
  if (S_ISBLK(st.st_mode)) return not_a("a block device");
  if (S_ISSOCK(st.st_mode)) return not_a("a socket");
  if (!S_ISREG(st.st_mode)) return fmt::format("is not a regular file (a {} file is needed)", what);
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > max_bytes)
    return fmt::format("is {} bytes, more than the {} a {} file may have", size, max_bytes, what);
  return std::nullopt;
}

std::string errno_problem(int error) {
  if (error == ENOENT) return "does not exist";
  if (error == ENOTDIR) return "does not exist (a part of its path is not a directory)";
  return std::string("cannot be read: ") + std::strerror(error);
}

}  // namespace

std::optional<std::string> input_file_problem(const std::filesystem::path& path,
                                              std::string_view what, std::uint64_t max_bytes) {
  if (path.empty()) return std::string("no file named (the path is empty)");
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return errno_problem(errno);
  return status_problem(st, what, max_bytes);
}

void check_input_file(const std::filesystem::path& path, std::string_view what,
                      std::uint64_t max_bytes) {
  if (auto problem = input_file_problem(path, what, max_bytes))
    throw InputError(path.string(), "", *problem);
}

std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                            std::uint64_t max_bytes) {
  const std::string file = path.string();
  check_input_file(path, what, max_bytes);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw InputError(file, "", errno_problem(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw InputError(file, "", errno_problem(errno));
  if (auto problem = status_problem(st, what, max_bytes)) throw InputError(file, "", *problem);
  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  std::size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(file, "", std::string("cannot be read: ") + std::strerror(errno));
    if (n == 0) break;  // the file shrank while it was read
    got += static_cast<std::size_t>(n);
  }
  text.resize(got);
  return text;
}

}  // namespace floornav::io_detail
