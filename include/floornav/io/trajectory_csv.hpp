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
/// (s, m, m, rad, m/s, rad/s, rad/s, rad/s, mode name). Numbers are the shortest text that reads
/// back to the same double, so the file is exact and the same on every machine.
std::string trajectory_to_csv(const RunResult& result);

/// A fleet's trajectories in one file: the same columns and a last one, `robot` (its name),
/// robot after robot, each in time order.
std::string trajectory_to_csv(const FleetResult& result);

/// The same text handed to `sink` in pieces of about 1 MiB (robot by robot), so that a big
/// fleet's file need not be held in memory at once.
void trajectory_csv_pieces(const FleetResult& result,
                           const std::function<void(std::string_view)>& sink);

}  // namespace floornav
