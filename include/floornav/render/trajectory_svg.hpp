#pragma once
/// @file
/// trajectory.svg (CONTRACT.md): a picture of a run: the world, the path coloured by mode, the
/// switch points, start, goals, the final pose, a legend and a scale bar.

#include <string>
#include <string_view>

#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// Colour (`#rrggbb`) used for the mode called `name`: go_to_goal blue, follow_boundary_cw
/// orange, follow_boundary_ccw green, avoid_obstacle red, blended purple, stop black; other
/// names get `fallback_index`-th colour of a spare palette.
std::string_view mode_color(std::string_view name, int fallback_index = 0);

/// A standalone SVG document (UTF-8, starts with `<svg`), about 900 px wide. World y points up.
/// The view holds the world's extent, the path, the start and the goals; text is XML-escaped.
/// The path is decimated to about 5000 points and an occupancy grid larger than 4 million cells
/// is drawn downsampled, so the file stays small for long runs and big maps.
std::string render_trajectory_svg(const Scenario& scenario, const RunResult& result);

/// The same picture for a fleet: every robot's path (coloured by mode), starts, goals and final
/// bodies, small fleets' robots named at their start. The path points are shared among the
/// robots (about 5000 in all, at least 50 each), so a big fleet's file stays small.
std::string render_fleet_svg(const Scenario& scenario, const FleetResult& result);

}  // namespace floornav
