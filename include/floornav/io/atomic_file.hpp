#pragma once
/// @file
/// Writing output files so that a reader never sees half of one: the content goes to a temporary
/// file beside the target, which is then renamed over it.

#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace floornav {

/// Writes `content` to `path` atomically: to `path.tmp.<pid>.<counter>` in the same directory,
/// then renamed over `path` (replacing any old file). Every write and the close are checked.
/// On failure (no such directory, permission denied, disk full) the temporary file is removed and
/// OutputError(path, "<reason>") is thrown; `path` is left as it was.
void write_file_atomically(const std::filesystem::path& path, std::string_view content);

/// The same for content too big to hold at once: `produce` is called with a sink and hands it the
/// content piece by piece; the same checks and the same atomic rename.
void write_file_atomically(
    const std::filesystem::path& path,
    const std::function<void(const std::function<void(std::string_view)>& sink)>& produce);

/// Creates `dir` and its missing parents. Throws OutputError(dir, reason) when that fails or when
/// `dir` exists but is not a directory.
void ensure_directory(const std::filesystem::path& dir);

/// The files of one output folder, which appear together or not at all. Each is written (with
/// every write checked) into a staging folder inside `dir`, then commit() renames each into
/// `dir`, within one folder and one filesystem. The folder (and missing parents) is created when
/// the first file is written, not before. A failure before commit(), or no commit() at all,
/// removes the staging folder and every folder it created, and leaves the files already in `dir`
/// as they were. (A process killed outright between two renames of commit() can still leave part
/// of a set: microseconds, not the seconds a write takes.)
class OutputFolder {
 public:
  /// `owned` names every file this kind of output may write: commit() removes those of them in
  /// `dir` that this set did not write (an earlier run's trajectory.html when this run wrote
  /// none), so that no stale file sits beside the new ones; other files are never touched.
  /// Throws InputError for ".", "" or "..", OutputError when `dir` exists and is not a folder.
  explicit OutputFolder(std::filesystem::path dir, std::vector<std::string> owned = {});
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Writes the file `name` (a plain file name) into the set. Two threads may write two files
  /// of the set at once (run.mcap is written beside the others).
  void write(const std::string& name, std::string_view content);
  void write(const std::string& name,
             const std::function<void(const std::function<void(std::string_view)>& sink)>& produce);
  /// Makes every file of the set appear in `dir` (created if needed), replacing older ones, and
  /// removes the owned files the set did not write.
  void commit();

  const std::filesystem::path& dir() const { return dir_; }

 private:
  void stage();
  std::filesystem::path dir_;
  std::vector<std::string> owned_;
  std::filesystem::path staging_;
  std::vector<std::filesystem::path> created_;  ///< folders made by stage(), outermost first
  std::vector<std::string> names_;
  bool committed_{false};
  std::mutex mutex_;  ///< write() from two threads: staging_, created_ and names_
};

/// `name` as a safe folder or file name: letters, digits, '-', '_' and '.' kept, anything else
/// (a '/', "..", a control character) replaced by '_', no leading '.', at most 120 bytes, never
/// empty. A scenario's name is used for its output folder (out/<name>) through this, so that no
/// name can write outside out/.
std::string safe_file_name(std::string_view name);

}  // namespace floornav
