#include "floornav/nav/heading_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "floornav/geometry/angle.hpp"

namespace floornav {

UnicycleCommand track_velocity(const Vec2& u, double theta, double v_max, const PidGains& gains,
                               PidState& pid, double dt, bool slow_when_turning) {
  const double speed = u.norm();
  if (speed <= 1e-9) {
    pid = {};  // no reference heading: hold still and forget the history
    return {0.0, 0.0};
  }
  const double theta_d = std::atan2(u.y(), u.x());   // eq. 5.28
  const double e = wrap_angle(theta_d - theta);      // eq. 5.14
  const double omega = pid_step(gains, pid, e, dt);  // eqs. 5.13/5.15
  double v = std::min(speed, v_max);                 // V = |u|, capped
  if (slow_when_turning) v *= std::max(0.0, std::cos(e));
  return {v, omega};
}

}  // namespace floornav
