#pragma once
/// @file
/// Writing a run's files (summary.json, trajectory.csv, trajectory.svg, trajectory.html) and its
/// one-line report.

#include <filesystem>
#include <string>

#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// Which files `write_run_outputs` writes.
struct OutputSelection {
  bool summary{true};
  bool csv{true};
  bool svg{true};
  bool html{true};  ///< trajectory.html, the replay (only when the trajectory was recorded)
};

/// Makes `scenario` record what the selected files need: with html, the sensor ranges for the
/// replay's beams (sim.record_ranges_every = replay_ranges_interval, unless already set).
/// Recording changes no result.
void prepare_outputs(Scenario& scenario, const OutputSelection& which = {});

/// Writes the selected files into `dir` (created if needed), each atomically.
void write_run_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                       const RunResult& result, const OutputSelection& which = {});

/// "factory-delivery: reached in 41.3 s, path 7.92 m, min clearance 0.061 m, 6 switches".
std::string describe_run(const RunResult& result);

/// Times `simulate` and fills in the result's wall_time.
RunResult run_timed(const Scenario& scenario);

/// A fleet's files in `dir`: summary.json (fleet_summary_to_json), trajectory.csv (with a robot
/// column), trajectory.svg (every robot's path) and trajectory.html (the replay).
void write_fleet_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                         const FleetResult& result, const OutputSelection& which = {});

/// "aisles: 8 robots, 8 reached, 0 collided, 24/24 deliveries in 61.2 s, min clearance 0.021 m".
std::string describe_fleet(const FleetResult& result);

/// Times `simulate_fleet` on `threads` threads (0: all cores) and fills in wall_time.
FleetResult run_fleet_timed(const Scenario& scenario, int threads = 0);

}  // namespace floornav
