#pragma once
/// @file
/// The 2D vector type used everywhere, and the few operations Eigen does not spell out.

#include <Eigen/Core>
#include <cmath>

namespace floornav {

/// A point or direction in the plane, metres (world frame unless stated).
using Vec2 = Eigen::Vector2d;

/// z-component of the 3D cross product; > 0 when `b` lies counter-clockwise of `a`.
inline double cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// `v` rotated counter-clockwise by the angle whose cosine and sine are `c` and `s`.
inline Vec2 rotate(const Vec2& v, double c, double s) {
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}
/// `v` rotated by `phi` radians counter-clockwise: R(phi) v, the rotation of eqs. 5.22-5.24.
inline Vec2 rotate(const Vec2& v, double phi) {
  // cos(+-0) = 1 and sin(+-0) = +-0 exactly: the same bits without the library's calls.
  if (phi == 0.0) return rotate(v, 1.0, phi);
  return rotate(v, std::cos(phi), std::sin(phi));
}

/// `v` rotated by +pi/2 exactly (no trigonometry, so no rounding).
inline Vec2 rotate_ccw90(const Vec2& v) {
  return {-v.y(), v.x()};
}
/// `v` rotated by -pi/2 exactly.
inline Vec2 rotate_cw90(const Vec2& v) {
  return {v.y(), -v.x()};
}

/// True when both coordinates are finite.
inline bool is_finite(const Vec2& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y());
}

/// `v / |v|`, or the zero vector when `|v|` is below `tiny` (never NaN).
inline Vec2 normalized_or_zero(const Vec2& v, double tiny = 1e-12) {
  const double n = v.norm();
  return n > tiny ? Vec2(v / n) : Vec2::Zero();
}

}  // namespace floornav
