#include "floornav/robot/body_clearance.hpp"

#include <array>

namespace floornav {

namespace {

constexpr std::size_t kMaxVertices = 16;  // footprints with more are checked as the disc

bool checked_as_disc(const RobotSpec& robot) {
  return robot.footprint.empty() || robot.footprint.size() > kMaxVertices;
}

double footprint_clearance(const World& world, const RobotSpec& robot, const Pose2& pose) {
  constexpr double kExactReach = 0.5;  // m; farther than this only a lower bound is needed
  std::array<Vec2, kMaxVertices> corners;
  for (std::size_t i = 0; i < robot.footprint.size(); ++i)
    corners[i] = pose.transform_point(robot.footprint[i]);
  return world.polygon_clearance(std::span<const Vec2>(corners.data(), robot.footprint.size()),
                                 kExactReach);
}

}  // namespace

double body_clearance(const World& world, const RobotSpec& robot, const Pose2& pose) {
  if (checked_as_disc(robot)) return world.clearance(pose.position) - robot.body_radius;
  return footprint_clearance(world, robot, pose);
}

double body_clearance(const World& world, const RobotSpec& robot, const Pose2& pose,
                      ClearanceHint& hint) {
  if (checked_as_disc(robot)) return world.clearance(pose.position, hint) - robot.body_radius;
  return footprint_clearance(world, robot, pose);
}

}  // namespace floornav
