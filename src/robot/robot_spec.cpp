#include "floornav/robot/robot_spec.hpp"

#include <algorithm>
#include <cmath>

#include "floornav/geometry/angle.hpp"

namespace floornav {

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
