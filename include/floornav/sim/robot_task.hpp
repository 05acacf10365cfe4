#pragma once
/// @file
/// One robot's part in a run: its body, where it starts, its route, and how it decides.

#include <string>
#include <vector>

#include "floornav/geometry/pose2.hpp"
#include "floornav/nav/controller.hpp"
#include "floornav/robot/robot_spec.hpp"

namespace floornav {

struct RobotTask {
  std::string name{"robot"};
  RobotSpec robot{};
  Pose2 start{};
  std::vector<Vec2> goals;  ///< visited in order
  ControllerConfig controller{};
};

}  // namespace floornav
