#pragma once
/// @file
/// Many runs in parallel: `results.jsonl` (one summary per line, in case order, written as the
/// cases finish), `aggregate.json` (the totals) and `sweep.json` (which sweep, and which shard of
/// it, the folder holds). Shards of one sweep are joined by merge_batches, which refuses anything
/// but all the shards of one sweep (or says that the result is partial).

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "floornav/scenario/scenario.hpp"

namespace floornav {

/// The most cases a sweep may have (the largest --limit), and the most shards it may be split
/// into. sweep.json files claiming more are refused before anything is sized by them.
inline constexpr std::size_t kMaxSweepCases = 1000000000;
inline constexpr int kMaxShards = 1000000;

/// Which cases of a batch get pictures (an SVG and an HTML replay), or bags (--mcap).
enum class BatchPictures { None, Failed, All };
/// Which sweep a batch belongs to. The id is a fingerprint of everything the sweep's lines depend
/// on (inputs, their content, options, floornav's version; not the shard, the job count or
/// --limit), so that the shards of one sweep, and a single run of it, carry the same id; `cases`
/// says how many cases the sweep has (merge requires the same count in every shard).
struct SweepInfo {
  std::string id;  ///< "" when the caller has none (then merge cannot check the shards)
  int shard{1};    ///< this batch is shard `shard` of `shards` (1-based)
  int shards{1};
  std::size_t cases{0};  ///< cases in the whole sweep (after --limit)
};

/// How far a batch has come (BatchOptions::progress).
struct BatchProgress {
  std::size_t done{0};   ///< cases with a result line (resumed ones included)
  std::size_t total{0};  ///< cases of this call
  double elapsed{0.0};   ///< s since the cases began to run
  bool finished{false};  ///< the last report: no more cases run
};

struct BatchOptions {
  int jobs{0};                    ///< worker threads; 0 = all cores
  std::filesystem::path out_dir;  ///< results.jsonl, aggregate.json and sweep.json go here
  /// Told how far the batch has come, about ten times a second and once more (`finished`) when
  /// it stops running cases; from run_batch's own thread, never from a worker. The command line
  /// draws its progress bar with it.
  std::function<void(const BatchProgress&)> progress;
  bool timing{true};   ///< false: wall_time is written as 0, so files compare equal
  bool resume{false};  ///< keep the cases already in results.jsonl; run only the rest
  /// Cases without a given `optimal_length` get the grid optimum (scenario_optimum: octile A*
  /// on a raster of the world, string-pulled) as `optimal_length`, source "grid_astar".
  bool optimum{true};
  /// Set (e.g. by SIGINT) to stop: running cases are abandoned within a step, none is written.
  const std::atomic<bool>* stop{nullptr};
  std::vector<std::string> overrides;  ///< the --set values as given, for each line's provenance
  SweepInfo sweep;                     ///< written to sweep.json; checked by --resume and merge
  /// Failed (status other than reached) or all cases get `case-NNNNN-<name>.svg` and `.html` in
  /// pictures_dir. Those runs record their trajectory and ranges as they go (the same results:
  /// recording moves nothing), so a failure is drawn without running it again.
  BatchPictures pictures{BatchPictures::None};
  std::filesystem::path pictures_dir;
  /// The same for bags: `case-NNNNN-<name>.mcap` (run.mcap's content) in mcap_dir; those runs
  /// record their trajectory and ranges too. An earlier batch's `case-NNNNN-*` pictures and bags
  /// in these folders are removed, except (with `resume`) those of the finished cases kept.
  BatchPictures mcap{BatchPictures::None};
  std::filesystem::path mcap_dir;
};

struct BatchCase {
  Scenario scenario;
  std::string source;  ///< the file (and row) it came from, for the results line
  std::size_t id{0};   ///< the case number in the whole sweep (kept across --shard)
  /// m, from a benchmark file (a .scen row; source "scen"), for path_efficiency = optimal /
  /// driven. Without it, run_batch computes the grid optimum unless options.optimum is off.
  std::optional<double> optimal_length;
  std::optional<double> optimal_time;  ///< s, for the BARN score
  std::vector<std::string> swept;      ///< a parameter sweep's "key=value" settings of this case
};

/// Cases made when they run, so that a sweep of a million .scen rows never holds a million
/// scenarios: `ids` are the case numbers to run (ascending), `make(id)` makes one.
struct CaseList {
  std::vector<std::size_t> ids;
  std::function<BatchCase(std::size_t id)> make;
};

/// The BARN challenge's score: success * t_opt / clip(t, 2 t_opt, 8 t_opt).
double barn_score(bool success, double time, double optimal_time);

/// Keeps the cases of shard `k` of `n` (1-based): every n-th case starting at k - 1.
std::vector<BatchCase> select_shard(std::vector<BatchCase> cases, int k, int n);

/// The case numbers of shard `k` of `n` among `count` cases: k - 1, k - 1 + n, ...
std::vector<std::size_t> shard_ids(std::size_t count, int k, int n);

struct MergeOutcome {
  nlohmann::ordered_json aggregate;
  std::size_t merged{0};            ///< cases in the merged results.jsonl
  std::size_t total{0};             ///< cases in the sweep
  std::vector<int> missing_shards;  ///< shards not given (with allow_partial)
  bool complete{false};
};

/// Joins the results.jsonl of batch folders into `out_dir`, in case order, after checking that
/// they are shards of one sweep (sweep.json: the same id and shard count, each shard once, each
/// complete, each line a case of its shard). Anything else throws InputError naming what is
/// wrong or missing; with `allow_partial`, missing shards and unfinished cases are allowed and
/// the aggregate says `complete: false`.
MergeOutcome merge_batches(std::span<const std::filesystem::path> dirs,
                           const std::filesystem::path& out_dir, bool allow_partial = false);

struct BatchOutcome {
  std::size_t completed{0};  ///< cases with a result line (including resumed ones)
  std::size_t total{0};
  std::size_t resumed{0};  ///< lines kept from an earlier run (--resume): these did not run
  std::size_t ran{0};      ///< cases simulated by this call
  bool interrupted{false};
  nlohmann::ordered_json aggregate;
};

/// Runs every case, in stages: the resumed folder's lines (--resume), the folder itself, the
/// workers with the ordered writer of results.jsonl, then the aggregate. Throws OutputError when
/// the output cannot be written (at the first failed write: the workers are stopped, nothing more
/// runs), InputError for a folder that cannot be resumed.
BatchOutcome run_batch(const CaseList& cases, const BatchOptions& options);
BatchOutcome run_batch(std::span<const BatchCase> cases, const BatchOptions& options);

/// Runs one case as run_batch does (the grid optimum and the pictures per `options`) and returns
/// its results.jsonl line; writes no results file. What the run throws (a user controller's
/// exception) passes through.
nlohmann::ordered_json run_batch_case(const BatchCase& c, const BatchOptions& options);

/// The text of a batch folder's sweep.json for shard `sweep.shard` of `sweep.shards` of the sweep,
/// holding `shard_cases` of its cases (what run_batch writes; merge and --resume read it).
std::string sweep_json_text(const SweepInfo& sweep, std::size_t shard_cases);

/// The totals of a list of result lines (as written to results.jsonl).
nlohmann::ordered_json aggregate_results(const std::vector<nlohmann::ordered_json>& lines);

}  // namespace floornav
