#include "floornav/scenario/presets.hpp"

#include <array>
#include <cmath>

#include "floornav/geometry/angle.hpp"

namespace floornav {

namespace {

double rpm_to_rad_s(double rpm) {
  return rpm * 2.0 * kPi / 60.0;
}

struct Mount {
  double x, y, deg;
};
std::vector<RangeSensorSpec> ring(std::span<const Mount> mounts, double min_range, double max_range,
                                  double cone_deg = 0.0, int cone_rays = 1) {
  std::vector<RangeSensorSpec> out;
  for (const Mount& m : mounts)
    out.push_back({{Vec2(m.x, m.y), deg_to_rad(m.deg)},
                   min_range,
                   max_range,
                   deg_to_rad(cone_deg),
                   cone_rays});
  return out;
}

// QuickBot (the course's robot, Sim.I.Am): 5 IR sensors on the chassis edge, 4-30 cm.
RobotSpec quickbot() {
  static constexpr Mount kIr[] = {{-0.0474, 0.0534, 90},
                                  {0.0613, 0.0386, 45},
                                  {0.0664, 0.0, 0},
                                  {0.0613, -0.0386, -45},
                                  {-0.0474, -0.0534, -90}};
  RobotSpec r;
  r.drive = {.wheel_radius = 0.0325,
             .track_width = 0.09925,
             .max_wheel_speed = rpm_to_rad_s(130.0),
             .min_wheel_speed = 0.0};
  r.body_radius = 0.075;
  r.sensors = ring(kIr, 0.04, 0.30);
  // Acceleration limits: our choice (no published figure), for the dwa kind.
  r.max_acceleration = 1.0;
  r.max_angular_acceleration = 10.0;
  return r;
}

// K-Team Khepera III (Sim.I.Am): 9 IR sensors, 2-20 cm, 13 cm diameter, ~0.3 m/s.
RobotSpec khepera3() {
  static constexpr Mount kIr[] = {
      {-0.038, 0.048, 128}, {0.019, 0.064, 75},     {0.050, 0.050, 42},
      {0.070, 0.017, 13},   {0.070, -0.017, -13},   {0.050, -0.050, -42},
      {0.019, -0.064, -75}, {-0.038, -0.048, -128}, {-0.048, 0.0, 180}};
  RobotSpec r;
  r.drive = {.wheel_radius = 0.0205,
             .track_width = 0.08841,
             .max_wheel_speed = 0.3148 / 0.0205,
             .min_wheel_speed = 0.0};
  r.body_radius = 0.0704;
  r.sensors = ring(kIr, 0.02, 0.20);
  // Acceleration limits: our choice (no published figure), for the dwa kind.
  r.max_acceleration = 1.0;
  r.max_angular_acceleration = 10.0;
  return r;
}

// Adept MobileRobots Pioneer 3-DX: 16 sonars (8 front, 8 rear, ARIA's layout), 0.1-5 m, 15 deg
// cones; 1.2 m/s.
RobotSpec pioneer_p3dx() {
  static constexpr Mount kSonar[] = {
      {0.069, 0.136, 90},    {0.114, 0.119, 50},     {0.148, 0.078, 30},     {0.166, 0.027, 10},
      {0.166, -0.027, -10},  {0.148, -0.078, -30},   {0.114, -0.119, -50},   {0.069, -0.136, -90},
      {-0.157, -0.136, -90}, {-0.203, -0.119, -130}, {-0.237, -0.078, -150}, {-0.255, -0.027, -170},
      {-0.255, 0.027, 170},  {-0.237, 0.078, 150},   {-0.203, 0.119, 130},   {-0.157, 0.136, 90}};
  RobotSpec r;
  r.drive = {.wheel_radius = 0.0975,
             .track_width = 0.331,
             .max_wheel_speed = 1.2 / 0.0975,
             .min_wheel_speed = 0.0};
  r.body_radius = 0.26;
  r.sensors = ring(kSonar, 0.1, 5.0, 15.0, 3);
  // Acceleration limits: ARIA's defaults, 300 mm/s^2 and 100 deg/s^2.
  r.max_acceleration = 0.3;
  r.max_angular_acceleration = 1.745;
  return r;
}

// ROBOTIS TurtleBot3 Burger: LDS-01 lidar, 360 beams, 0.12-3.5 m; 0.22 m/s.
RobotSpec turtlebot3_burger() {
  RobotSpec r;
  r.drive = {.wheel_radius = 0.033,
             .track_width = 0.160,
             .max_wheel_speed = 0.22 / 0.033,
             .min_wheel_speed = 0.0};
  r.body_radius = 0.105;
  r.sensors = make_lidar(360, 2.0 * kPi, 0.12, 3.5, {Vec2(-0.032, 0.0), 0.0});
  // Acceleration limits: ROBOTIS's DWA configuration for the Burger.
  r.max_acceleration = 2.5;
  r.max_angular_acceleration = 3.2;
  return r;
}

// Clearpath Jackal (the BARN robot): 270-degree lidar with 720 beams, 2.0 m/s.
RobotSpec jackal() {
  RobotSpec r;
  r.drive = {.wheel_radius = 0.098,
             .track_width = 0.37559,
             .max_wheel_speed = 2.0 / 0.098,
             .min_wheel_speed = 0.0};
  r.body_radius = 0.25;
  // BARN's passages are sized for the Jackal's rectangular footprint, 0.508 x 0.430 m.
  r.footprint = {{-0.254, -0.215}, {0.254, -0.215}, {0.254, 0.215}, {-0.254, 0.215}};
  r.sensors = make_lidar(720, deg_to_rad(270.0), 0.1, 30.0, {Vec2(0.12, 0.0), 0.0});
  // Acceleration limits: our choice (no manufacturer figure checked).
  r.max_acceleration = 2.0;
  r.max_angular_acceleration = 3.0;
  return r;
}

struct PresetRow {
  std::string_view name;
  RobotSpec (*robot)();
  /// The controller defaults: speeds and clearances scale with the robot's size, speed and
  /// sensor range (the QuickBot row is NavigationParams' own defaults).
  NavigationParams navigation;
};

// clang-format off
const std::array<PresetRow, 5> kPresets{{
  {"quickbot",          quickbot,          {.v0 = 0.15, .gtg_a = 40.0, .d_o = 0.12, .d_fb = 0.08, .k_fb = 10.0, .d_unsafe = 0.03, .hysteresis = 0.02,  .progress_margin = 0.02, .epsilon = 0.05, .blend_near = 0.03, .blend_far = 0.15, .obstacle_memory = 1.0, .obstacle_range = 0.0}},
  {"khepera3",          khepera3,          {.v0 = 0.1,  .gtg_a = 40.0, .d_o = 0.09, .d_fb = 0.06, .k_fb = 10.0, .d_unsafe = 0.02, .hysteresis = 0.015, .progress_margin = 0.02, .epsilon = 0.04, .blend_near = 0.02, .blend_far = 0.12, .obstacle_memory = 1.0, .obstacle_range = 0.0}},
  {"pioneer_p3dx",      pioneer_p3dx,      {.v0 = 0.5,  .gtg_a = 4.0,  .d_o = 0.6,  .d_fb = 0.45, .k_fb = 3.0,  .d_unsafe = 0.15, .hysteresis = 0.1,   .progress_margin = 0.1,  .epsilon = 0.2,  .blend_near = 0.15, .blend_far = 0.8,  .obstacle_memory = 2.0, .obstacle_range = 1.5}},
  {"turtlebot3_burger", turtlebot3_burger, {.v0 = 0.2,  .gtg_a = 10.0, .d_o = 0.3,  .d_fb = 0.2,  .k_fb = 5.0,  .d_unsafe = 0.06, .hysteresis = 0.04,  .progress_margin = 0.02, .epsilon = 0.1,  .blend_near = 0.06, .blend_far = 0.35, .obstacle_memory = 0.0, .obstacle_range = 0.6}},
  {"jackal",            jackal,            {.v0 = 1.0,  .gtg_a = 2.0,  .d_o = 0.5,  .d_fb = 0.3,  .k_fb = 4.0,  .d_unsafe = 0.08, .hysteresis = 0.06,  .progress_margin = 0.1,  .epsilon = 0.3,  .blend_near = 0.08, .blend_far = 0.6,  .obstacle_memory = 0.0, .obstacle_range = 1.0}},
}};
// clang-format on

constexpr std::array<std::string_view, 5> kPresetNames{"quickbot", "khepera3", "pioneer_p3dx",
                                                       "turtlebot3_burger", "jackal"};

}  // namespace

std::span<const std::string_view> robot_preset_names() {
  return kPresetNames;
}

std::optional<RobotPreset> find_robot_preset(std::string_view name) {
  for (const PresetRow& row : kPresets)
    if (row.name == name) {
      RobotPreset p{row.robot(), row.navigation};
      p.robot.preset = std::string(row.name);
      return p;
    }
  return std::nullopt;
}

}  // namespace floornav
