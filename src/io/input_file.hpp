#pragma once
// Opening input files safely: whatever a path names (a missing file, a folder, a FIFO that would
// block forever, /dev/zero that never ends, a file of gigabytes) is named for what it is before a
// byte is read, and nothing larger than a format's documented limit is ever read. Private to the
// io library.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace floornav::io_detail {

/// Size limits of the input files, in bytes (docs/SCENARIOS.md, "Limits").
inline constexpr std::uint64_t kMaxScenarioBytes = 16u << 20;
inline constexpr std::uint64_t kMaxMapYamlBytes = 1u << 20;
inline constexpr std::uint64_t kMaxXmlBytes = 64u << 20;
inline constexpr std::uint64_t kMaxImageBytes = 1u << 30;
inline constexpr std::uint64_t kMaxMovingAiMapBytes = 160u << 20;
inline constexpr std::uint64_t kMaxScenBytes = 128u << 20;
inline constexpr std::uint64_t kMaxNpyBytes = 256u << 20;

/// Why `path` cannot be read as a `what` file of at most `max_bytes`, or nullopt when it can:
/// "does not exist", "is a directory, not a MovingAI map file", "is a FIFO (named pipe), not a
/// ...", "is a character device, not a ...", "is 3000000000 bytes, more than the 16777216 a
/// scenario file may have", "cannot be read: Permission denied". Never opens the file.
std::optional<std::string> input_file_problem(const std::filesystem::path& path,
                                              std::string_view what, std::uint64_t max_bytes);

/// Throws InputError(path, "", problem) when input_file_problem finds one.
void check_input_file(const std::filesystem::path& path, std::string_view what,
                      std::uint64_t max_bytes);

/// The whole file, read after the same checks, made on the open file itself (opened
/// non-blocking, so that a FIFO put in its place between a check and the open cannot block).
/// Throws InputError naming `path`.
std::string read_input_file(const std::filesystem::path& path, std::string_view what,
                            std::uint64_t max_bytes);

}  // namespace floornav::io_detail
