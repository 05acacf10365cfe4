#pragma once
/// @file
/// Angle wrapping, eq. 5.14.

#include <cmath>
#include <numbers>

namespace floornav {

inline constexpr double kPi = std::numbers::pi;

/// Wraps `angle` into (-pi, pi] as `atan2(sin e, cos e)` does (eq. 5.14), but exactly for angles
/// already in range so that wrapping is idempotent bit for bit.
inline double wrap_angle(double angle) {
  if (angle > -kPi && angle <= kPi) return angle;
  const double wrapped = std::atan2(std::sin(angle), std::cos(angle));
  return wrapped <= -kPi ? kPi : wrapped;  // atan2 can return -pi itself; the interval is (-pi, pi]
}

inline constexpr double deg_to_rad(double deg) {
  return deg * kPi / 180.0;
}
inline constexpr double rad_to_deg(double rad) {
  return rad * 180.0 / kPi;
}

}  // namespace floornav
