#pragma once
/// @file
/// Finds the robot models (RobotModel) that agents share: robots of one kind (body, sensors,
/// controller parameters equal) read one copy of each, so that a step over many robots touches
/// one set of them rather than one per robot (at a thousand robots, a copy each costs a few more
/// cache misses per robot step).

#include <cstddef>
#include <vector>

#include "floornav/sim/robot_agent.hpp"
#include "floornav/sim/robot_task.hpp"

namespace floornav {

class RobotModels {
 public:
  /// Past this many distinct models a task keeps its own copies, so finding one stays cheap.
  static constexpr std::size_t kMaxModels = 64;

  /// The shared model equal to `task`'s robot and parameters, made from `task` when it is the
  /// first of its kind. `task` must outlive every agent given the model.
  RobotModel find(const RobotTask& task);

 private:
  std::vector<RobotModel> robots_;  ///< the robot and sensor layout of each (params unused)
  std::vector<const NavigationParams*> params_;
};

}  // namespace floornav
