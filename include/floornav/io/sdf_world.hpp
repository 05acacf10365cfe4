#pragma once
/// @file
/// Gazebo worlds (.world / .sdf, e.g. the BARN benchmark): the static boxes and cylinders,
/// projected onto the ground plane.

#include <filesystem>
#include <string>
#include <vector>

#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// The 2D obstacles of a Gazebo world, world frame (m).
struct SdfWorld {
  std::vector<Circle> circles;              ///< cylinders (and spheres), by radius
  std::vector<std::vector<Vec2>> polygons;  ///< boxes as rotated rectangles, counter-clockwise
  /// What the file holds that could not be read, and where: "line 12: <include> of
  /// 'model://cafe' is not read ...", non-static models with collisions, meshes and other shapes.
  /// A scenario refuses a world with any (the robot would drive through them).
  std::vector<std::string> skipped;
};

/// Loads the `<collision>` geometry of every static `<model>` (`<static>1</static>` or `true`,
/// also inherited by nested models) of the `<world>` (or of a bare `<sdf><model>` file). Poses
/// compose in 2D: model, then link, then collision, each `<pose>` "x y z roll pitch yaw" giving
/// (x, y, yaw); roll and pitch are ignored; `degrees='true'` reads the angles in degrees. A model
/// also listed under `<world><state>` takes its pose from there (Gazebo saves the live pose
/// there); each model is emitted once. Ground planes and `<include>`s of the sun or the ground
/// plane hold nothing to hit; any other `<include>`, non-static models with collisions, meshes
/// and other shapes are listed in `skipped`. Throws InputError naming the line for malformed XML,
/// poses that are not 6 finite numbers or use another frame, non-positive sizes and duplicate model
/// names.
SdfWorld load_sdf_world(const std::filesystem::path& file);

}  // namespace floornav
