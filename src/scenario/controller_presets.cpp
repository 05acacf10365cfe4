#include "floornav/scenario/controller_presets.hpp"

#include <array>

namespace floornav {

namespace {
constexpr std::array<std::string_view, 2> kNames{"factory", "chapter"};
}  // namespace

bool apply_controller_preset(std::string_view name, ControllerConfig& config) {
  if (name == "factory") {
    config.kind = "hybrid";
    config.planner.kind = PlannerKind::AStar;
    config.planner.map = PlannerMap::Known;
    // The safety layer is every robot's guard: the planner's own footprint guard, which passes
    // unicycle commands that ORCA cannot bend, stays off (BARN's template turns it on).
    config.planner.guard_horizon = 0.0;
    config.safety.enabled = true;
    config.avoidance.kind = RobotAvoidance::Orca;
    return true;
  }
  if (name == "chapter") {
    config.kind = "hybrid";
    config.planner.kind = PlannerKind::None;
    config.planner.guard_horizon = 0.0;
    config.safety.enabled = false;
    config.avoidance.kind = RobotAvoidance::None;
    return true;
  }
  return false;
}

std::span<const std::string_view> controller_preset_names() {
  return kNames;
}

}  // namespace floornav
