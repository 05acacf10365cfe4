#pragma once
/// @file
/// World files of the Sim.I.Am / pySimiam course simulators (e.g. pySimiam `worlds/week7.xml`):
/// robots with a starting pose, and polygonal obstacles.

#include <filesystem>
#include <string>
#include <vector>

#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// A `<robot type="...">` element.
struct CourseRobot {
  std::string type;        ///< e.g. "QuickBot", "Khepera3"
  Pose2 pose;              ///< world frame, m and rad
  std::string supervisor;  ///< the `<supervisor type>` if given, e.g. "week7.QBFullSupervisor"
};

/// The robots and obstacles of a course world.
struct CourseWorld {
  std::vector<CourseRobot> robots;
  std::vector<std::vector<Vec2>> obstacles;  ///< world-frame polygons, in file order, >= 3 points
};

/// Loads `<simulation>` with `<robot type>` (holding `<pose x y theta>`; other children such as
/// `<supervisor>` are allowed) and `<obstacle>` (holding `<pose x y theta>` and `<geometry>` with
/// `<point x y>` in the obstacle's frame, which this maps to the world frame). theta is in
/// radians. Other elements (`<marker>`, ...) are ignored. Throws InputError naming the line for
/// malformed XML, missing or non-numeric attributes and obstacles with fewer than 3 points.
CourseWorld load_course_world(const std::filesystem::path& xml);

}  // namespace floornav
