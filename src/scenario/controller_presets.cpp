#include "floornav/scenario/controller_presets.hpp"

#include <array>

namespace floornav {

namespace {
constexpr std::array<std::string_view, 2> kNames{"factory", "chapter"};
}  // namespace

bool apply_controller_preset(std::string_view name, ControllerConfig& config) {
  NavigationParams& p = config.params;
  if (name == "factory") {
    config.kind = "hybrid";
    p.planner.kind = PlannerKind::AStar;
    p.planner.map = PlannerMap::Known;
    p.planner.guard_horizon = 0.5;  // docs/BENCHMARKS.md, BARN: the value chosen on a third
    p.safety.enabled = true;
    p.robot_avoidance = RobotAvoidance::Orca;
    return true;
  }
  if (name == "chapter") {
    config.kind = "hybrid";
    p.planner.kind = PlannerKind::None;
    p.planner.guard_horizon = 0.0;
    p.safety.enabled = false;
    p.robot_avoidance = RobotAvoidance::None;
    return true;
  }
  return false;
}

std::span<const std::string_view> controller_preset_names() {
  return kNames;
}

}  // namespace floornav
