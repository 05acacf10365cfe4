#pragma once
/// @file
/// Range sensors (IR, sonar, lidar beams) and the obstacle points they report, in the world frame.
/// (The simulator casts the same sensors as fans found once per sensor list: the same ranges and
/// noise draws, bit for bit.)

#include <span>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/oriented_box.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// One range sensor, mounted on the robot.
struct RangeSensorSpec {
  Pose2 mount;             ///< pose in the robot frame (metres, radians)
  double min_range{0.02};  ///< metres; closer readings clamp to this (what real IR/sonar do)
  double max_range{0.30};  ///< metres; "nothing seen" reads as this
  double cone_angle{0.0};  ///< full cone width, radians; 0 for a single beam (lidar, IR)
  int cone_rays{1};        ///< rays cast across the cone (the nearest return wins)
  bool operator==(const RangeSensorSpec&) const = default;
};

/// One sensor's axis in the world frame at one step: `robot.compose(mount)`, with its unit
/// direction computed once for both the ray cast and the obstacle point.
struct SensorBeam {
  Vec2 origin{Vec2::Zero()};  ///< m, world frame
  Vec2 dir{1.0, 0.0};         ///< unit vector, (cos theta, sin theta) to within 1e-13
  double theta{0.0};          ///< rad, world frame, wrapped to (-pi, pi]
};

/// Casts every sensor of `sensors` from `robot` into `world`, writing one range per sensor to
/// `ranges` (same size as `sensors`). With `noise_stddev` > 0, Gaussian noise (metres) from
/// `rng` is added before clamping to [min_range, max_range]. No allocation.
void sense_ranges(const World& world, const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                  double noise_stddev, Rng& rng, std::span<double> ranges);

/// Turns readings into world-frame obstacle points: one per sensor that saw something (range
/// below its max). Returns how many were written to `points` (sized at least `sensors.size()`;
/// the element after them may be overwritten too).
std::size_t ranges_to_points(const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                             std::span<const double> ranges, std::span<Vec2> points);

}  // namespace floornav
