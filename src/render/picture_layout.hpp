#pragma once
/// @file
/// Private to the render module: what a picture shows and where. A `Track` is one robot's run
/// (its task and its result), the `Extent` the part of the world that must be in view, the
/// `View` the map from metres (y up) to pixels (y down).

#include <limits>
#include <span>
#include <string>
#include <string_view>

#include "floornav/robot/robot_spec.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/sim/run_result.hpp"
#include "floornav/world/world.hpp"

namespace floornav::render_detail {

/// One robot's run as a picture draws it: the robot's task (its body, start, goals and epsilon),
/// its result and, in a fleet, its colour (empty for a lone robot, whose path is coloured by
/// mode).
struct Track {
  const RobotTask* task{nullptr};
  const RunResult* run{nullptr};
  std::string color;
};

/// An axis-aligned box that grows to hold what is added (metres).
struct Extent {
  double xmin{std::numeric_limits<double>::infinity()};
  double ymin{std::numeric_limits<double>::infinity()};
  double xmax{-std::numeric_limits<double>::infinity()};
  double ymax{-std::numeric_limits<double>::infinity()};

  void add(double x, double y, double pad = 0.0);
  bool valid() const { return xmin <= xmax && ymin <= ymax; }
};

/// World (metres, y up) to picture (pixels, y down).
struct View {
  double xmin{0.0}, ymax{0.0};
  double scale{1.0};  ///< px per metre
  double left{0.0}, top{0.0};
  double width{0.0}, height{0.0};  ///< px of the world's extent

  double x(double wx) const { return left + (wx - xmin) * scale; }
  double y(double wy) const { return top + (ymax - wy) * scale; }
};

/// m from the robot's centre to the farthest point of its body (disc or footprint).
double body_reach(const RobotSpec& robot);

/// True when the world has anything to draw (bounds, shapes or a map).
bool world_has_content(const World& world);

/// Everything that must be in the picture: the world (when given), every track's start, goals
/// (with their epsilon discs), path and final body. Never a sliver: the shorter side is at
/// least a quarter of the longer one.
Extent picture_extent(const World* world, std::span<const Track> tracks);

/// The view that fits `extent` into at most `max_width` x `max_height` px, keeping proportions.
View fit_view(const Extent& extent, double max_width, double max_height);

/// The round length (1, 2 or 5 times a power of ten, metres) whose bar is at most 160 px.
double scale_bar_length(double px_per_m);

/// Rough width (px) of `text` in a sans-serif font of `font_size` px, for laying out legends.
double text_width(std::string_view text, double font_size);

}  // namespace floornav::render_detail
