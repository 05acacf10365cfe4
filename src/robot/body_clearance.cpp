#include "floornav/robot/body_clearance.hpp"

#include <array>

namespace floornav {

double body_clearance(const World& world, const RobotSpec& robot, const Pose2& pose) {
  constexpr std::size_t kMaxVertices = 16;
  constexpr double kExactReach = 0.5;  // m; farther than this only a lower bound is needed
  if (robot.footprint.empty() || robot.footprint.size() > kMaxVertices)
    return world.clearance(pose.position) - robot.body_radius;
  std::array<Vec2, kMaxVertices> corners;
  for (std::size_t i = 0; i < robot.footprint.size(); ++i)
    corners[i] = pose.transform_point(robot.footprint[i]);
  return world.polygon_clearance(std::span<const Vec2>(corners.data(), robot.footprint.size()),
                                 kExactReach);
}

}  // namespace floornav
