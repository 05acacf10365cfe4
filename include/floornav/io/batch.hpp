#pragma once
/// @file
/// Many runs in parallel: `results.jsonl` (one summary per line, in case order, written as the
/// cases finish) and `aggregate.json` (the totals).

#include <atomic>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "floornav/sim/scenario.hpp"

namespace floornav {

struct BatchOptions {
  int jobs{0};                    ///< worker threads; 0 = all cores
  std::filesystem::path out_dir;  ///< results.jsonl and aggregate.json go here
  bool progress{false};           ///< a progress bar on stderr
  bool timing{true};              ///< false: wall_time is written as 0, so files compare equal
  bool resume{false};             ///< skip cases already in results.jsonl
  const std::atomic<bool>* stop{nullptr};  ///< set (e.g. by SIGINT) to stop taking new cases
};

struct BatchCase {
  Scenario scenario;
  std::string source;  ///< the file (and row) it came from, for the results line
};

struct BatchOutcome {
  std::size_t completed{0};  ///< cases with a result line (including resumed ones)
  std::size_t total{0};
  bool interrupted{false};
  nlohmann::ordered_json aggregate;
};

/// Runs every case; throws InputError when the output cannot be written.
BatchOutcome run_batch(std::span<const BatchCase> cases, const BatchOptions& options);

/// The totals of a list of result lines (as written to results.jsonl).
nlohmann::ordered_json aggregate_results(const std::vector<nlohmann::ordered_json>& lines);

}  // namespace floornav
