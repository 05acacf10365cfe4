#pragma once
/// @file
/// summary.json (CONTRACT.md): one object per run, also one line of a batch's results.jsonl.

#include <nlohmann/json.hpp>

#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// Transitions listed in a summary; the rest are counted in `mode_switches` only.
inline constexpr std::size_t kSummaryMaxTransitions = 1000;

/// The run as JSON: first the CONTRACT.md keys in their order (scenario, status, reached_goal,
/// collided, sim_time, path_length, min_clearance, mode_switches, mode_time, steps, wall_time),
/// then goals_reached, goal_count, chatter_episodes, first_chatter_time (null when none),
/// final_pose [x, y, theta], wait_time (s the body moved slower than 1 cm/s), transitions [{t,
/// from, to, guard, x, y}] (mode and guard names; the first kSummaryMaxTransitions, with
/// `transitions_truncated: true` when there were more). `mode_time` lists only the modes that ran
/// (time > 0), in mode order, seconds. A number that is NaN or infinite is written as null.
nlohmann::ordered_json summary_to_json(const RunResult& result);

/// Collisions listed in a fleet summary; the rest are counted only.
inline constexpr std::size_t kSummaryMaxCollisions = 1000;

/// A fleet run as JSON. The CONTRACT.md keys first, for the fleet as a whole: status (reached
/// when every robot completed its route, else collision if any collided, else stuck if any
/// was, else timeout), reached_goal (all), collided (any), sim_time (until the last robot
/// finished), path_length and mode_switches (sums), min_clearance (smallest), mode_time (sums
/// by mode name), steps (world steps), wall_time. Then `fleet` {robots, reached, collided,
/// timeout, stuck, deliveries, delivery_count, deliveries_per_minute, robot_steps,
/// robot_collisions, world_collisions, (with people or forklifts) person_collisions,
/// forklift_collisions, wait_time (summed)}, with people or forklifts `crowd` {people, forklifts,
/// person_contacts, forklift_contacts, intrusions, intrusion_time, personal_space, min_person_gap,
/// people_blocked_time, forklift_stopped_time}, `collisions` [{t, robot, other, kind}] (names;
/// other is null for the world; kind world, robot, person or forklift; the first
/// kSummaryMaxCollisions) and `robots`: each robot's own summary.
nlohmann::ordered_json fleet_summary_to_json(const FleetResult& result);

}  // namespace floornav
