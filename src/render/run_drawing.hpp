#pragma once
/// @file
/// Private to the render module: a run in an SVG picture: the path (coloured by mode for a lone
/// robot, in the robot's colour in a fleet), the mode switches, the bodies (footprint polygon or
/// disc, with a heading tick) and the goals (flags numbered in route order).

#include <cstddef>
#include <string_view>

#include "picture_layout.hpp"
#include "svg_text.hpp"

namespace floornav::render_detail {

inline constexpr double kMinRobotRadius = 6.0;  ///< px: a tiny robot is still drawn visibly
inline constexpr const char* kGoalFill = "#f4b400";
inline constexpr const char* kGoalStroke = "#8a6d00";

/// The path of `track`, with samples closer than half a pixel dropped and, past `max_points`,
/// thinned evenly (the first and last sample of every mode run are always kept).
void draw_path(SvgOut out, const Track& track, const View& v, std::size_t max_points);

/// One hollow circle per switch point; a switch within 8 px of one already drawn is left out, so
/// that chatter shows as a chain of markers rather than a black smear.
void draw_switches(SvgOut out, const RunResult& run, const View& v);

/// A disc of radius `r` px at pixel (x, y) with a tick from the centre along `theta` (world
/// radians): a robot without a footprint, and the legend's icons.
void draw_disc_robot(SvgOut out, double x, double y, double r, double theta, std::string_view fill,
                     double fill_opacity, std::string_view stroke);

/// The robot's body at world pose (x, y, theta): its footprint polygon when it has one (with the
/// heading tick), else its disc (at least kMinRobotRadius px).
void draw_body(SvgOut out, const RobotSpec& robot, double x, double y, double theta, const View& v,
               std::string_view fill, double fill_opacity, std::string_view stroke);

/// A goal flag with its foot at pixel (x, y), `size` px wide.
void draw_flag(SvgOut out, double x, double y, double size, std::string_view fill = kGoalFill,
               std::string_view stroke = kGoalStroke);

/// The goal discs (radius epsilon) of `task`, dashed.
void draw_goal_areas(SvgOut out, const RobotTask& task, const View& v, std::string_view color);

/// The goal flags of `task`, numbered in route order when `numbered` (in the robot's colour for
/// a fleet's robot; `color` empty for a lone robot).
void draw_goal_flags(SvgOut out, const RobotTask& task, const View& v, std::string_view color,
                     bool numbered);

}  // namespace floornav::render_detail
