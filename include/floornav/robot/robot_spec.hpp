#pragma once
/// @file
/// A robot: its differential-drive base, its body, its range sensors. The published presets
/// (robot and controller defaults together) are in scenario/presets.hpp.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/sensing/range_sensor.hpp"

namespace floornav {

struct RobotSpec {
  std::string preset;                    ///< the preset it started from ("" for none)
  DiffDriveParams drive{};               ///< R, L, wheel limits (eqs. 5.5-5.11)
  double body_radius{0.075};             ///< m: the body disc (guards, clearance, collision)
  std::vector<Vec2> footprint;           ///< robot-frame polygon for collision; empty: the disc
  std::vector<RangeSensorSpec> sensors;  ///< in the robot frame
  double sensor_noise{0.0};              ///< m: std. dev. of Gaussian range noise
  /// m/s^2 and rad/s^2: how fast the base can change its forward speed and turn rate. The
  /// simulator's kinematic model does not enforce them (commands act at once, as in the
  /// chapter); the `dwa` controller builds its dynamic window from them.
  double max_acceleration{1.0};
  double max_angular_acceleration{5.0};
  bool operator==(const RobotSpec&) const = default;
};

/// `beams` single-beam sensors spread evenly over `fov` radians centred on the mount's heading
/// (a planar lidar); both ends included when fov < 2 pi, evenly round the circle otherwise.
std::vector<RangeSensorSpec> make_lidar(int beams, double fov, double min_range, double max_range,
                                        const Pose2& mount);

}  // namespace floornav
