#pragma once
// Running the built floornav from a test: its exit status and everything it printed, fresh
// temporary folders (one per process, so parallel runs of the suite do not meet), and files.
#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace cli_harness {

namespace fs = std::filesystem;

struct Output {
  int status;
  std::string text;  // stdout and stderr
};

/// `wrapper`, when given, is a command that runs floornav (e.g. one that drops privileges).
/// `stdout_to`, when given, is where floornav's standard output goes (then `text` is its stderr).
inline Output floornav(const std::string& args, const std::string& wrapper = "",
                       const std::string& stdout_to = "") {
  const std::string cmd = (wrapper.empty() ? "" : wrapper + " ") + std::string(FLOORNAV_BINARY) +
                          " " + args + " 2>&1" + (stdout_to.empty() ? "" : " >" + stdout_to);
  Output out{0, ""};
  FILE* p = popen(cmd.c_str(), "r");
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) out.text += buf.data();
  const int raw = pclose(p);
  out.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return out;
}

/// An empty (removed) folder floornav_<name>_<pid> in the system's temporary folder.
inline fs::path fresh_temp_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("floornav_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

inline std::string scenario(const std::string& file) {
  return std::string(FLOORNAV_SCENARIO_DIR) + "/" + file;
}

inline std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace cli_harness
