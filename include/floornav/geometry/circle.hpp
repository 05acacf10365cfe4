#pragma once
/// @file
/// Solid discs: circular obstacles (and point obstacles, radius 0), section 5.4.1.

#include <cmath>

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

// The ray against a disc, intersect_ray(const Circle&, ...), is in geometry/ray.hpp with the
// library's other ray tests.

}  // namespace floornav
