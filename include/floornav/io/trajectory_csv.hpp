#pragma once
/// @file
/// trajectory.csv (CONTRACT.md): one row per recorded step.

#include <functional>
#include <string>
#include <string_view>

#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// The header `t,x,y,theta,v,omega,w_left,w_right,mode`, then one row per TrajectorySample
/// (s, m, m, rad, m/s, rad/s, rad/s, rad/s, mode name), then the extra columns the run recorded
/// (RunResult::extra_columns, SimConfig::record), a value that does not apply left empty.
/// Numbers are the shortest text that reads back to the same double, so the file is exact and
/// the same on every machine.
std::string trajectory_to_csv(const RunResult& result);

/// The same text handed to `sink` in pieces of about 1 MiB.
void trajectory_csv_pieces(const RunResult& result,
                           const std::function<void(std::string_view)>& sink);

/// A fleet's trajectories in one file: the same columns with `robot` (its name) after `mode`,
/// robot after robot, each in time order; the extra columns are those of the robot with the
/// most (robots with fewer sensors leave the last range_i empty).
std::string trajectory_to_csv(const FleetResult& result);

/// The same text handed to `sink` in pieces of about 1 MiB (robot by robot), so that a big
/// fleet's file need not be held in memory at once.
void trajectory_csv_pieces(const FleetResult& result,
                           const std::function<void(std::string_view)>& sink);

/// transitions.csv: `t,robot,from,to,guard,x,y`, one row per logged transition of the
/// controller (s, robot name, mode names, the guard's name or empty for a mode change without a
/// named guard, m, m), in time order. `robot` names the lone robot's row.
std::string transitions_to_csv(const RunResult& result, std::string_view robot);

/// A fleet's transitions, every robot's, in time order (robot order breaks ties).
std::string transitions_to_csv(const FleetResult& result);

}  // namespace floornav
