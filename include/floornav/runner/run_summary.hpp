#pragma once
/// @file
/// The summary of a run as `run` writes it (summary.json) and as `batch` writes each line of
/// results.jsonl: the same keys in both, docs/OUTPUTS.md lists them. The run's own keys
/// (summary_json.hpp), then what it was asked to do (controller, robot, start, goals), how it
/// compares with the optimum when one is known, any warnings, and its provenance (provenance.hpp:
/// floornav_version, seed, overrides, config).

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "floornav/runner/scenario_optimum.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// What a summary says besides the run itself.
struct RunContext {
  std::vector<std::string> overrides;    ///< the --set values as given, in order
  std::optional<Optimum> optimum;        ///< the grid optimum, when it was computed
  std::optional<double> optimal_length;  ///< m, from a benchmark file (a .scen row)
  std::optional<double> optimal_time;    ///< s, BARN's, for its score
  std::vector<std::string> swept;        ///< a sweep's "key=value" settings for this case
};

/// The robot whose grid optimum a summary gives: a lone robot's task in a scenario with a world;
/// nullptr for a fleet, or a scenario without a world or robots (no optimum). The one guard of
/// compute_optimum and the batch's cached optimum.
const RobotTask* optimum_task(const Scenario& scenario);

/// The grid optimum of a lone-robot scenario (scenario_optimum for its robot's body, start and
/// goals); nullopt where optimum_task gives no robot.
std::optional<Optimum> compute_optimum(const Scenario& scenario);

/// One line saying that the goal cannot be reached on the known map, when `optimum` says so
/// (unreachable, or no free cell near the start or a goal); nullopt otherwise.
std::optional<std::string> reachability_warning(const Scenario& scenario, const Optimum& optimum);

/// summary.json for a lone robot: summary_to_json's keys, then controller, robot, start, goals,
/// the optimum keys (optimal_length, path_efficiency, optimal_source, optimal_octile_length or
/// optimal_status, optimal_cell_size) when one is known, optimal_time and score (BARN), swept,
/// warnings (when any), and the provenance keys.
nlohmann::ordered_json run_summary(const Scenario& scenario, const RunResult& result,
                                   const RunContext& context);

/// summary.json for a fleet: fleet_summary_to_json's keys, then controller and robot (the first
/// robot's), swept, warnings, and the provenance keys.
nlohmann::ordered_json fleet_run_summary(const Scenario& scenario, const FleetResult& result,
                                         const RunContext& context);

}  // namespace floornav
