#pragma once
/// @file
/// Writing output files so that a reader never sees half of one: the content goes to a temporary
/// file beside the target, which is then renamed over it.

#include <filesystem>
#include <functional>
#include <string_view>

namespace floornav {

/// Writes `content` to `path` atomically: to `path.tmp.<pid>.<counter>` in the same directory,
/// then renamed over `path` (replacing any old file). Every write and the close are checked.
/// On failure (no such directory, permission denied, disk full) the temporary file is removed and
/// InputError(path, "", "cannot write: <reason>") is thrown; `path` is left as it was.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// The same for content too big to hold at once: `produce` is called with a sink and hands it the
/// content piece by piece; the same checks and the same atomic rename.
void write_file_atomically(
    const std::filesystem::path& path,
    const std::function<void(const std::function<void(std::string_view)>& sink)>& produce);

/// Creates `dir` and its missing parents. Throws InputError(dir, "", "cannot create directory:
/// <reason>") when that fails or when `dir` exists but is not a directory.
void ensure_directory(const std::filesystem::path& dir);

}  // namespace floornav
