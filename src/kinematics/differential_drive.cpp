#include "floornav/kinematics/differential_drive.hpp"

#include <algorithm>
#include <cmath>

namespace floornav {

UnicycleCommand wheels_to_unicycle(const DiffDriveParams& p, const WheelSpeeds& w) {
  return {p.wheel_radius * (w.right + w.left) / 2.0,
          p.wheel_radius * (w.right - w.left) / p.track_width};
}

WheelSpeeds unicycle_to_wheels(const DiffDriveParams& p, const UnicycleCommand& u) {
  return {(2.0 * u.v - u.omega * p.track_width) / (2.0 * p.wheel_radius),
          (2.0 * u.v + u.omega * p.track_width) / (2.0 * p.wheel_radius)};
}

WheelSpeeds saturate_wheels(const DiffDriveParams& p, const UnicycleCommand& u) {
  const double w_max = p.max_wheel_speed;
  const double omega = std::clamp(u.omega, -max_turn_rate(p), max_turn_rate(p));
  const double v = std::clamp(u.v, -max_forward_speed(p), max_forward_speed(p));
  WheelSpeeds w = unicycle_to_wheels(p, {v, omega});
  // Shift both wheels by the same amount: that changes V only, never omega.
  const double hi = std::max(w.left, w.right);
  const double lo = std::min(w.left, w.right);
  double shift = 0.0;
  if (hi > w_max)
    shift = w_max - hi;
  else if (lo < -w_max)
    shift = -w_max - lo;
  w.left += shift;
  w.right += shift;
  // Rounding can leave a wheel a hair beyond its limit.
  w.left = std::clamp(w.left, -w_max, w_max);
  w.right = std::clamp(w.right, -w_max, w_max);
  auto stall = [&](double x) { return std::abs(x) < p.min_wheel_speed ? 0.0 : x; };
  w.left = stall(w.left);
  w.right = stall(w.right);
  return w;
}

}  // namespace floornav
