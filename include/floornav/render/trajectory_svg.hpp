#pragma once
/// @file
/// trajectory.svg (CONTRACT.md): a picture of a run: the world (unknown map cells hatched, apart
/// from obstacles), the path, the switch points, start, numbered goals, the final body (its
/// footprint polygon when it has one), a legend and a scale bar.

#include <string>

#include "floornav/render/palette.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// A standalone SVG document (UTF-8, starts with `<svg`), about 900 px wide. World y points up.
/// The view holds the world's extent, the path, the start and the goals; text is XML-escaped.
/// The path is coloured by mode, decimated to about 5000 points, and an occupancy grid larger
/// than 4 million cells is drawn downsampled, so the file stays small for long runs and big maps.
std::string render_trajectory_svg(const Scenario& scenario, const RunResult& result);

/// The same picture for a fleet: each robot in its own colour (robot_color) with a legend of
/// robot names, its path, start, goals (numbered in its route order) and final body; small
/// fleets' robots named at their start. The path points are shared among the robots (about 5000
/// in all, at least 50 each), so a big fleet's file stays small.
std::string render_fleet_svg(const Scenario& scenario, const FleetResult& result);

}  // namespace floornav
