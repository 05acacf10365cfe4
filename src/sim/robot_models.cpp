#include "floornav/sim/robot_models.hpp"

#include <memory>

#include "floornav/sensing/sensor_fans.hpp"

namespace floornav {

RobotModel RobotModels::find(const RobotTask& task) {
  RobotModel model;
  for (const RobotModel& m : robots_)
    if (*m.robot == task.robot) {
      model = m;
      break;
    }
  if (!model.robot && robots_.size() < kMaxModels) {
    robots_.push_back({&task.robot, std::make_shared<const SensorLayout>(task.robot.sensors)});
    model = robots_.back();
  }
  for (const NavigationParams* p : params_)
    if (*p == task.controller.params) {
      model.params = p;
      break;
    }
  if (!model.params && params_.size() < kMaxModels)
    params_.push_back(model.params = &task.controller.params);
  return model;
}

}  // namespace floornav
