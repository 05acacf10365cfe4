#pragma once
/// @file
/// Many runs in parallel: `results.jsonl` (one summary per line, in case order, written as the
/// cases finish) and `aggregate.json` (the totals).

#include <atomic>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "floornav/scenario/scenario.hpp"

namespace floornav {

/// Which cases of a batch get pictures (an SVG and an HTML replay).
enum class BatchPictures { None, Failed, All };

struct BatchOptions {
  int jobs{0};                    ///< worker threads; 0 = all cores
  std::filesystem::path out_dir;  ///< results.jsonl and aggregate.json go here
  bool progress{false};           ///< a progress bar on stderr
  bool timing{true};              ///< false: wall_time is written as 0, so files compare equal
  bool resume{false};             ///< skip cases already in results.jsonl
  /// Cases without a given `optimal_length` get the grid optimum (scenario_optimum: octile A*
  /// on a raster of the world, string-pulled) as `optimal_length`, source "grid_astar".
  bool optimum{true};
  const std::atomic<bool>* stop{nullptr};  ///< set (e.g. by SIGINT) to stop taking new cases
  /// Failed (status other than reached) or all cases get `case-NNNNN-<name>.svg` and `.html` in
  /// pictures_dir. Those runs record their trajectory and ranges as they go (the same results:
  /// recording moves nothing), so a failure is drawn without running it again.
  BatchPictures pictures{BatchPictures::None};
  std::filesystem::path pictures_dir;
};

struct BatchCase {
  Scenario scenario;
  std::string source;  ///< the file (and row) it came from, for the results line
  std::size_t id{0};   ///< the case number in the whole sweep (kept across --shard)
  /// m, from a benchmark file (a .scen row; source "scen"), for path_efficiency = optimal /
  /// driven. Without it, run_batch computes the grid optimum unless options.optimum is off.
  std::optional<double> optimal_length;
  std::optional<double> optimal_time;  ///< s, for the BARN score
};

/// The BARN challenge's score: success * t_opt / clip(t, 2 t_opt, 8 t_opt).
double barn_score(bool success, double time, double optimal_time);

/// Keeps the cases of shard `k` of `n` (1-based): every n-th case starting at k - 1.
std::vector<BatchCase> select_shard(std::vector<BatchCase> cases, int k, int n);

/// Joins the results.jsonl of several (sharded) batch folders into `out_dir`, in case order;
/// returns the aggregate. Throws InputError for unreadable or inconsistent inputs.
nlohmann::ordered_json merge_batches(std::span<const std::filesystem::path> dirs,
                                     const std::filesystem::path& out_dir);

struct BatchOutcome {
  std::size_t completed{0};  ///< cases with a result line (including resumed ones)
  std::size_t total{0};
  bool interrupted{false};
  nlohmann::ordered_json aggregate;
};

/// Runs every case; throws InputError when the output cannot be written.
BatchOutcome run_batch(std::span<const BatchCase> cases, const BatchOptions& options);

/// Runs one case as run_batch does (the grid optimum and the pictures per `options`) and returns
/// its results.jsonl line; writes no results file. What the run throws (a user controller's
/// exception) passes through.
nlohmann::ordered_json run_batch_case(const BatchCase& c, const BatchOptions& options);

/// The totals of a list of result lines (as written to results.jsonl).
nlohmann::ordered_json aggregate_results(const std::vector<nlohmann::ordered_json>& lines);

}  // namespace floornav
