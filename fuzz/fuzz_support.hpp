#pragma once
// What every fuzz target shares: a scratch folder for the loaders that read files, and the checks
// that an input error is reported honestly and that what loaded is finite. A violated check
// aborts, which libFuzzer reports as a finding, as it does any other crash or sanitizer error.

#include <stdlib.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/vec2.hpp"
#include "floornav/sim/crowd.hpp"

namespace floornav::fuzz {

/// A folder of this process's own (libFuzzer's -jobs and -fork run several), removed at exit.
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    std::string name = (std::filesystem::temp_directory_path() / "floornav_fuzz_XXXXXX").string();
    if (::mkdtemp(name.data()) == nullptr) {
      std::perror("floornav fuzz: mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return std::filesystem::path(name);
  }();
  return dir;
}

/// Writes `bytes` to `name` in the scratch folder and returns its path.
inline std::filesystem::path write_scratch(const std::string& name, std::string_view bytes) {
  const std::filesystem::path path = scratch_dir() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::perror("floornav fuzz: cannot write the scratch file");
    std::abort();
  }
  return path;
}

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "floornav fuzz finding: %s\n", what.c_str());
  std::abort();
}

/// The CLI prints what() as its one line of error: it must say something, on one line.
inline void check_message(const InputError& e) {
  const std::string_view what = e.what();
  if (what.empty() || e.detail.empty()) finding("an InputError without a message");
  if (what.find('\n') != std::string_view::npos || what.find('\r') != std::string_view::npos)
    finding("an InputError message of more than one line: " + std::string(what));
}

inline void check_finite(double v, const char* what) {
  if (!std::isfinite(v)) finding(std::string("a non-finite ") + what + " was accepted");
}

inline void check_finite(const Vec2& v, const char* what) {
  check_finite(v.x(), what);
  check_finite(v.y(), what);
}

/// Every sample and path length of the people's and forklifts' tracks is finite.
inline void check_crowd(const CrowdResult& crowd) {
  for (const auto* group : {&crowd.people, &crowd.forklifts})
    for (const CrowdTrack& t : *group) {
      for (const CrowdSample& p : t.samples)
        for (const double v : {p.t, p.x, p.y, p.theta}) check_finite(v, "crowd sample");
      check_finite(t.path_length, "crowd path length");
    }
}

}  // namespace floornav::fuzz
