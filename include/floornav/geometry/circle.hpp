#pragma once
/// @file
/// Solid discs: circular obstacles (and point obstacles, radius 0), section 5.4.1.

#include <cmath>
#include <optional>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// A solid disc; a point obstacle is a circle of radius 0 ("a point with a safety radius").
struct Circle {
  Vec2 center{Vec2::Zero()};
  double radius{0.0};  ///< metres, >= 0
};

/// Signed distance from `p` to the disc's boundary: negative inside.
inline double signed_distance(const Circle& c, const Vec2& p) {
  return (p - c.center).norm() - c.radius;
}

/// The boundary point of `c` nearest to `p` (the centre itself for a point obstacle).
Vec2 nearest_point(const Circle& c, const Vec2& p);

/// Distance along the ray `origin + t dir` (unit `dir`) to the disc's boundary, `t >= 0`;
/// 0 when the origin is inside. Inline: lidars test it per beam against other robots' bodies.
inline std::optional<double> intersect_ray(const Circle& c, const Vec2& origin, const Vec2& dir) {
  const Vec2 m = origin - c.center;
  const double cc = m.squaredNorm() - c.radius * c.radius;
  if (cc <= 0.0) return 0.0;  // starts inside or on the boundary
  const double b = m.dot(dir);
  if (b > 0.0) return std::nullopt;  // pointing away
  const double disc = b * b - cc;
  if (disc < 0.0) return std::nullopt;
  return -b - std::sqrt(disc);
}

}  // namespace floornav
