#pragma once
/// @file
/// The published robot presets: each a robot (base, body, sensors, from its maker's specs) and
/// the controller defaults that suit its speed and sensor range, kept in one table.

#include <optional>
#include <span>
#include <string_view>

#include "floornav/nav/navigation_params.hpp"
#include "floornav/robot/robot_spec.hpp"

namespace floornav {

/// A preset: the robot and the supervisor defaults that suit it.
struct RobotPreset {
  RobotSpec robot;
  NavigationParams navigation;
};

/// The preset called `name` (quickbot, khepera3, pioneer_p3dx, turtlebot3_burger, jackal).
std::optional<RobotPreset> find_robot_preset(std::string_view name);
std::span<const std::string_view> robot_preset_names();

}  // namespace floornav
