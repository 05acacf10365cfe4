#pragma once
/// @file
/// Writing a run's files (summary.json, trajectory.csv, trajectory.svg, trajectory.html) and its
/// one-line report.

#include <atomic>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "floornav/runner/run_summary.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// Every file a run's output folder may hold (write_run_outputs, write_fleet_outputs): a run
/// into the folder of an earlier run removes those of them it does not write itself.
const std::vector<std::string>& run_output_files();

/// A run records at most this many rows (robots, people and forklifts, times steps) and this
/// many numbers in all (rows x columns): 1e7 rows hold about 0.7 GB in memory and 1 GB of CSV.
inline constexpr double kMaxRecordedRows = 1e7;
inline constexpr double kMaxRecordedValues = 2e8;

/// Refuses (InputError naming `file` and sim.record_trajectory or --record) a run whose
/// recording would exceed those limits, before it starts: every robot's trajectory rows, every
/// person's and forklift's crowd.csv rows, the --record columns.
void check_recording_limits(const Scenario& scenario, const std::string& file);

/// Which files `write_run_outputs` writes.
struct OutputSelection {
  bool summary{true};
  bool csv{true};
  bool svg{true};
  bool html{true};         ///< trajectory.html, the replay (only when the trajectory was recorded)
  bool transitions{true};  ///< transitions.csv
  /// run.mcap, the run as a ROS 2 bag (io/run_mcap.hpp; only when the trajectory was recorded).
  /// Its sensor topics hold the ranges the run recorded (sim.record_ranges_every).
  bool mcap{false};
};

/// Makes `scenario` record what the selected files need: with html, the sensor ranges for the
/// replay's beams (replay_ranges_interval); with mcap, the trajectory and the ranges for the
/// bag's sensor topics (mcap_ranges_interval). With both, the steps of either interval
/// (sim.record_ranges_also_every; the shorter alone when it divides the other): each takes its
/// own frames, the replay the same as without the bag. A record_ranges_every the scenario sets
/// is kept. Recording changes no result.
void prepare_outputs(Scenario& scenario, const OutputSelection& which = {});

/// Writes the selected files into `dir` (created if needed), all together or none
/// (OutputFolder): summary.json (run_summary with `context`), trajectory.csv, transitions.csv,
/// trajectory.svg, trajectory.html and run.mcap.
void write_run_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                       const RunResult& result, const RunContext& context,
                       const OutputSelection& which = {});
/// The same without provenance overrides or an optimum (RunContext{}).
void write_run_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                       const RunResult& result, const OutputSelection& which = {});

/// "factory-delivery: reached in 41.3 s, path 7.92 m, min clearance 0.061 m, 6 switches".
std::string describe_run(const RunResult& result);

/// Times `simulate` and fills in the result's wall_time.
RunResult run_timed(const Scenario& scenario);

/// The same, abandoned (nullopt) as soon as `stop` or `also` is set: both are read at every step.
std::optional<RunResult> run_timed(const Scenario& scenario, const std::atomic<bool>* stop,
                                   const std::atomic<bool>* also = nullptr);

/// A fleet's files in `dir`, all together or none: summary.json (fleet_run_summary),
/// trajectory.csv (with a robot column), transitions.csv, trajectory.svg (every robot's path),
/// trajectory.html (the replay), crowd.csv (people and forklifts, when there are any) and
/// run.mcap.
void write_fleet_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                         const FleetResult& result, const RunContext& context,
                         const OutputSelection& which = {});
void write_fleet_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                         const FleetResult& result, const OutputSelection& which = {});

/// "aisles: 8 robots, 8 reached, 0 collided, 24/24 deliveries in 61.2 s, min clearance 0.021 m".
std::string describe_fleet(const FleetResult& result);

/// Times `simulate_fleet` on `threads` threads (0: all cores) and fills in wall_time.
FleetResult run_fleet_timed(const Scenario& scenario, int threads = 0);

/// The same, abandoned (nullopt) once `stop` or `also` is set: read every 64 world steps.
std::optional<FleetResult> run_fleet_timed(const Scenario& scenario, int threads,
                                           const std::atomic<bool>* stop,
                                           const std::atomic<bool>* also = nullptr);

}  // namespace floornav
