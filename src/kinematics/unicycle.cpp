#include "floornav/kinematics/unicycle.hpp"

#include <cmath>

namespace floornav {

Pose2 integrate_unicycle(const Pose2& pose, const UnicycleCommand& u, double dt) {
  return integrate_unicycle(pose, u, dt, Vec2(std::cos(pose.theta), std::sin(pose.theta)));
}

Pose2 integrate_unicycle(const Pose2& pose, const UnicycleCommand& u, double dt,
                         const Vec2& heading) {
  const double dtheta = u.omega * dt;
  double fx, fy;  // displacement along and across the initial heading
  if (std::abs(dtheta) < 1e-9) {
    // sin(d)/d and (1 - cos d)/d by their series: the arc formula divides 0 by 0 here.
    const double d2 = dtheta * dtheta;
    fx = u.v * dt * (1.0 - d2 / 6.0);
    fy = u.v * dt * (dtheta / 2.0);
  } else {
    const double r = u.v / u.omega;
    fx = r * std::sin(dtheta);
    fy = r * (1.0 - std::cos(dtheta));
  }
  const double c = heading.x(), s = heading.y();
  return {pose.position + Vec2(c * fx - s * fy, s * fx + c * fy), wrap_angle(pose.theta + dtheta)};
}

}  // namespace floornav
