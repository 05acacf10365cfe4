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
  std::vector<std::string> skipped;         ///< what was left out and why, e.g. "model 'x': mesh"
};

/// Loads the `<collision>` geometry of every static `<model>` (`<static>1</static>` or `true`,
/// also inherited by nested models) of the `<world>` (or of a bare `<sdf><model>` file). Poses
/// compose in 2D: model, then link, then collision, each `<pose>` "x y z roll pitch yaw" giving
/// (x, y, yaw); roll and pitch are ignored. A model also listed under `<world><state>` takes its
/// pose from there (Gazebo saves the live pose there); each model is emitted once. Planes (the
/// ground) are ignored silently; `<include>`s, non-static models and meshes or other shapes are
/// listed in `skipped`. Throws InputError naming the line for malformed XML, poses that are not 6
/// finite numbers or use another frame, non-positive sizes and duplicate model names.
SdfWorld load_sdf_world(const std::filesystem::path& file);

}  // namespace floornav
