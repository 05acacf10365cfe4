#include "bench_cases.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/io/ros_map.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/validate.hpp"

namespace floornav {

std::filesystem::path aws_warehouse_map(const std::filesystem::path& maps_dir) {
  return maps_dir / "aws-robomaker-small-warehouse" / "005" / "map.yaml";
}

std::optional<Scenario> make_aws_scenario(const std::filesystem::path& maps_dir) {
  const std::filesystem::path map = aws_warehouse_map(maps_dir);
  std::error_code ec;
  if (!std::filesystem::exists(map, ec)) return std::nullopt;
  const RobotPreset preset = *find_robot_preset("turtlebot3_burger");
  Scenario s;
  s.name = "lidar360-aws-warehouse";
  WorldDesc desc;
  desc.grid = std::make_shared<const OccupancyGrid>(load_ros_map(map));
  s.world = std::make_shared<const World>(std::move(desc));
  RobotTask& t = s.robots.emplace_back();
  t.robot = preset.robot;
  t.controller.params = preset.navigation;
  t.start = {Vec2(-5.0, -8.5), 0.5 * kPi};
  t.goals = {Vec2(-5.0, 8.5)};
  s.sim.dt = 0.01;
  s.sim.t_max = 1.0e5;
  s.sim.record_trajectory = false;
  validate_scenario(s, map.string());
  return s;
}

}  // namespace floornav
