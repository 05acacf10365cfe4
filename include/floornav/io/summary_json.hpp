#pragma once
/// @file
/// summary.json (CONTRACT.md): one object per run, also one line of a batch's results.jsonl.

#include <nlohmann/json.hpp>

#include "floornav/sim/run_result.hpp"

namespace floornav {

/// Transitions listed in a summary; the rest are counted in `mode_switches` only.
inline constexpr std::size_t kSummaryMaxTransitions = 1000;

/// The run as JSON: first the CONTRACT.md keys in their order (scenario, status, reached_goal,
/// collided, sim_time, path_length, min_clearance, mode_switches, mode_time, steps, wall_time),
/// then goals_reached, goal_count, chatter_episodes, first_chatter_time (null when none),
/// final_pose [x, y, theta], transitions [{t, from, to, guard, x, y}] (mode and guard names; the
/// first kSummaryMaxTransitions, with `transitions_truncated: true` when there were more).
/// `mode_time` lists only the modes that ran (time > 0), in mode order, seconds. A number that
/// is NaN or infinite is written as null.
nlohmann::ordered_json summary_to_json(const RunResult& result);

}  // namespace floornav
