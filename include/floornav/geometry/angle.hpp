#pragma once
/// @file
/// Angle wrapping, eq. 5.14.

#include <algorithm>
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

/// atan2(y, x) to within 2e-6 rad, for (x, y) != 0: a degree-11 odd polynomial for atan on
/// [0, 1] (Abramowitz & Stegun style minimax; measured maximum error 1.7e-6), then the octant.
/// For culling with a margin, never for a result.
inline double coarse_atan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y);
  const double a = std::min(ax, ay) / std::max(ax, ay);
  const double s = a * a;
  double r =
      (((((-0.01172120 * s + 0.05265332) * s - 0.11643287) * s + 0.19354346) * s - 0.33262347) * s +
       0.99997726) *
      a;
  if (ay > ax) r = 0.5 * kPi - r;
  if (x < 0.0) r = kPi - r;
  return y < 0.0 ? -r : r;
}

inline constexpr double deg_to_rad(double deg) {
  return deg * kPi / 180.0;
}
inline constexpr double rad_to_deg(double rad) {
  return rad * 180.0 / kPi;
}

}  // namespace floornav
