#pragma once
/// @file
/// When a recorded run reached each of its goals, read back from its trajectory: the first row
/// (after the previous goal's) within epsilon of the goal, as the STOP guard sees it. The HTML
/// replay and the bag's goal topic show each robot's current goal from it.

#include <cstdint>
#include <vector>

#include "floornav/sim/robot_task.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// One entry per goal of `task`: the trajectory row at which it was reached, -1 from the first
/// goal not reached on (result.goals_reached of them are).
std::vector<std::int64_t> goal_reached_rows(const RobotTask& task, const RunResult& result);

}  // namespace floornav
