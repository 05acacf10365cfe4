#include "floornav/sim/robot_spec.hpp"

#include <array>
#include <cmath>

#include "floornav/geometry/angle.hpp"

namespace floornav {

namespace {
constexpr std::array<std::string_view, 5> kPresetNames{"quickbot", "khepera3", "pioneer_p3dx",
                                                       "turtlebot3_burger", "jackal"};

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
RobotPreset quickbot() {
  static constexpr Mount kIr[] = {{-0.0474, 0.0534, 90},
                                  {0.0613, 0.0386, 45},
                                  {0.0664, 0.0, 0},
                                  {0.0613, -0.0386, -45},
                                  {-0.0474, -0.0534, -90}};
  RobotPreset p;
  p.robot.preset = "quickbot";
  p.robot.drive = {.wheel_radius = 0.0325,
                   .track_width = 0.09925,
                   .max_wheel_speed = rpm_to_rad_s(130.0),
                   .min_wheel_speed = 0.0};
  p.robot.body_radius = 0.075;
  p.robot.sensors = ring(kIr, 0.04, 0.30);
  p.navigation = {};  // the defaults are tuned for the QuickBot
  return p;
}

// K-Team Khepera III (Sim.I.Am): 9 IR sensors, 2-20 cm, 13 cm diameter, ~0.3 m/s.
RobotPreset khepera3() {
  static constexpr Mount kIr[] = {
      {-0.038, 0.048, 128}, {0.019, 0.064, 75},     {0.050, 0.050, 42},
      {0.070, 0.017, 13},   {0.070, -0.017, -13},   {0.050, -0.050, -42},
      {0.019, -0.064, -75}, {-0.038, -0.048, -128}, {-0.048, 0.0, 180}};
  RobotPreset p;
  p.robot.preset = "khepera3";
  p.robot.drive = {.wheel_radius = 0.0205,
                   .track_width = 0.08841,
                   .max_wheel_speed = 0.3148 / 0.0205,
                   .min_wheel_speed = 0.0};
  p.robot.body_radius = 0.0704;
  p.robot.sensors = ring(kIr, 0.02, 0.20);
  p.navigation.v0 = 0.1;
  p.navigation.d_o = 0.09;
  p.navigation.d_fb = 0.06;
  p.navigation.d_unsafe = 0.02;
  p.navigation.hysteresis = 0.015;
  p.navigation.epsilon = 0.04;
  p.navigation.blend_far = 0.12;
  p.navigation.blend_near = 0.02;
  return p;
}

// Adept MobileRobots Pioneer 3-DX: 16 sonars (8 front, 8 rear, ARIA's layout), 0.1-5 m, 15 deg
// cones; 1.2 m/s.
RobotPreset pioneer_p3dx() {
  static constexpr Mount kSonar[] = {
      {0.069, 0.136, 90},    {0.114, 0.119, 50},     {0.148, 0.078, 30},     {0.166, 0.027, 10},
      {0.166, -0.027, -10},  {0.148, -0.078, -30},   {0.114, -0.119, -50},   {0.069, -0.136, -90},
      {-0.157, -0.136, -90}, {-0.203, -0.119, -130}, {-0.237, -0.078, -150}, {-0.255, -0.027, -170},
      {-0.255, 0.027, 170},  {-0.237, 0.078, 150},   {-0.203, 0.119, 130},   {-0.157, 0.136, 90}};
  RobotPreset p;
  p.robot.preset = "pioneer_p3dx";
  p.robot.drive = {.wheel_radius = 0.0975,
                   .track_width = 0.331,
                   .max_wheel_speed = 1.2 / 0.0975,
                   .min_wheel_speed = 0.0};
  p.robot.body_radius = 0.26;
  p.robot.sensors = ring(kSonar, 0.1, 5.0, 15.0, 3);
  p.navigation.v0 = 0.5;
  p.navigation.gtg_a = 4.0;
  p.navigation.d_o = 0.6;
  p.navigation.d_fb = 0.45;
  p.navigation.k_fb = 3.0;
  p.navigation.d_unsafe = 0.15;
  p.navigation.hysteresis = 0.1;
  p.navigation.progress_margin = 0.1;
  p.navigation.epsilon = 0.2;
  p.navigation.blend_near = 0.15;
  p.navigation.blend_far = 0.8;
  p.navigation.obstacle_memory = 2.0;
  p.navigation.obstacle_range = 1.5;
  return p;
}

// ROBOTIS TurtleBot3 Burger: LDS-01 lidar, 360 beams, 0.12-3.5 m; 0.22 m/s.
RobotPreset turtlebot3_burger() {
  RobotPreset p;
  p.robot.preset = "turtlebot3_burger";
  p.robot.drive = {.wheel_radius = 0.033,
                   .track_width = 0.160,
                   .max_wheel_speed = 0.22 / 0.033,
                   .min_wheel_speed = 0.0};
  p.robot.body_radius = 0.105;
  p.robot.sensors = make_lidar(360, 2.0 * kPi, 0.12, 3.5, {Vec2(-0.032, 0.0), 0.0});
  p.navigation.v0 = 0.2;
  p.navigation.gtg_a = 10.0;
  p.navigation.d_o = 0.3;
  p.navigation.d_fb = 0.2;
  p.navigation.k_fb = 5.0;
  p.navigation.d_unsafe = 0.06;
  p.navigation.hysteresis = 0.04;
  p.navigation.epsilon = 0.1;
  p.navigation.blend_near = 0.06;
  p.navigation.blend_far = 0.35;
  p.navigation.obstacle_memory = 0.0;
  p.navigation.obstacle_range = 0.6;
  return p;
}

// Clearpath Jackal (the BARN robot): 270-degree lidar with 720 beams, 2.0 m/s.
RobotPreset jackal() {
  RobotPreset p;
  p.robot.preset = "jackal";
  p.robot.drive = {.wheel_radius = 0.098,
                   .track_width = 0.37559,
                   .max_wheel_speed = 2.0 / 0.098,
                   .min_wheel_speed = 0.0};
  p.robot.body_radius = 0.25;
  // BARN's passages are sized for the Jackal's rectangular footprint, 0.508 x 0.430 m.
  p.robot.footprint = {{-0.254, -0.215}, {0.254, -0.215}, {0.254, 0.215}, {-0.254, 0.215}};
  p.robot.sensors = make_lidar(720, deg_to_rad(270.0), 0.1, 30.0, {Vec2(0.12, 0.0), 0.0});
  p.navigation.v0 = 1.0;
  p.navigation.gtg_a = 2.0;
  p.navigation.d_o = 0.5;
  p.navigation.d_fb = 0.3;
  p.navigation.k_fb = 4.0;
  p.navigation.d_unsafe = 0.08;
  p.navigation.hysteresis = 0.06;
  p.navigation.progress_margin = 0.1;
  p.navigation.epsilon = 0.3;
  p.navigation.obstacle_range = 1.0;
  p.navigation.blend_near = 0.08;
  p.navigation.blend_far = 0.6;
  p.navigation.obstacle_memory = 0.0;
  return p;
}
}  // namespace

std::span<const std::string_view> robot_preset_names() {
  return kPresetNames;
}

std::optional<RobotPreset> find_robot_preset(std::string_view name) {
  if (name == "quickbot") return quickbot();
  if (name == "khepera3") return khepera3();
  if (name == "pioneer_p3dx") return pioneer_p3dx();
  if (name == "turtlebot3_burger") return turtlebot3_burger();
  if (name == "jackal") return jackal();
  return std::nullopt;
}

std::vector<RangeSensorSpec> make_lidar(int beams, double fov, double min_range, double max_range,
                                        const Pose2& mount) {
  std::vector<RangeSensorSpec> out;
  out.reserve(static_cast<std::size_t>(std::max(beams, 0)));
  const bool full_circle = fov >= 2.0 * kPi - 1e-9;
  const double step = beams <= 1 ? 0.0 : fov / (full_circle ? beams : beams - 1);
  const double first = full_circle ? 0.0 : -0.5 * fov;
  for (int i = 0; i < beams; ++i) {
    const double a = beams <= 1 ? 0.0 : first + i * step;
    out.push_back({{mount.position, wrap_angle(mount.theta + a)}, min_range, max_range, 0.0, 1});
  }
  return out;
}

}  // namespace floornav
