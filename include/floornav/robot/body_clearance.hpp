#pragma once
/// @file
/// How far the robot's body is from the obstacles: the disc, or the footprint polygon when the
/// robot has one (a Jackal in BARN's narrow passages is a rectangle, not a disc).

#include "floornav/geometry/pose2.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// Signed clearance (m) between the body at `pose` and the world; <= 0 is a collision.
/// For a footprint it is exact within 0.5 m and a lower bound beyond.
double body_clearance(const World& world, const RobotSpec& robot, const Pose2& pose);
/// `body_clearance`, bit for bit, for a caller that checks the same body again nearby: a disc
/// body's query reuses and updates `hint` (a footprint's leaves it alone).
double body_clearance(const World& world, const RobotSpec& robot, const Pose2& pose,
                      ClearanceHint& hint);

}  // namespace floornav
