#include "floornav/sensing/range_sensor.hpp"

#include <algorithm>

namespace floornav {

void sense_ranges(const World& world, const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                  double noise_stddev, Rng& rng, std::span<double> ranges) {
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    const RangeSensorSpec& s = sensors[i];
    const Pose2 m = robot.compose(s.mount);
    double r = s.max_range;
    if (s.cone_rays <= 1 || s.cone_angle <= 0.0) {
      r = world.cast_ray(m.position, m.heading(), s.max_range);
    } else {
      for (int k = 0; k < s.cone_rays; ++k) {
        const double a =
            m.theta + s.cone_angle * (static_cast<double>(k) / (s.cone_rays - 1) - 0.5);
        r = std::min(r, world.cast_ray(m.position, Vec2(std::cos(a), std::sin(a)), s.max_range));
      }
    }
    // A sensor sees nothing beyond its range: noise is added only to real returns.
    if (noise_stddev > 0.0 && r < s.max_range) r += noise_stddev * rng.normal();
    ranges[i] = std::clamp(r, s.min_range, s.max_range);
  }
}

std::size_t ranges_to_points(const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                             std::span<const double> ranges, std::span<Vec2> points) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (ranges[i] >= sensors[i].max_range) continue;
    const Pose2 m = robot.compose(sensors[i].mount);
    points[n++] = m.position + ranges[i] * m.heading();
  }
  return n;
}

}  // namespace floornav
