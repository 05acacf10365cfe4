#pragma once
/// @file
/// Line segments: nearest point, distance, and ray intersection.

#include <algorithm>
#include <optional>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// The segment from `a` to `b` (metres).
struct Segment {
  Vec2 a{Vec2::Zero()};
  Vec2 b{Vec2::Zero()};

  double length() const { return (b - a).norm(); }
};

/// The point of `s` nearest to `p`; `s.a` for a degenerate segment.
inline Vec2 nearest_point(const Segment& s, const Vec2& p) {
  const Vec2 d = s.b - s.a;
  const double len2 = d.squaredNorm();
  if (len2 <= 0.0) return s.a;
  const double t = std::clamp((p - s.a).dot(d) / len2, 0.0, 1.0);
  return s.a + t * d;
}

/// Squared distance from `p` to segment `s` (distance() is its square root, to the bit): nearest
/// searches compare these and take one root at the end.
inline double squared_distance(const Segment& s, const Vec2& p) {
  return (p - nearest_point(s, p)).squaredNorm();
}

/// Euclidean distance from `p` to segment `s`.
inline double distance(const Segment& s, const Vec2& p) {
  return (p - nearest_point(s, p)).norm();
}

/// Distance along the ray `origin + t dir` (`dir` a unit vector) to where it first meets `s`,
/// if it does with `t >= 0`. A ray lying along the segment meets it at its nearer end.
/// (`ray_segment_hit` of ray.hpp, the form the casts use.)
std::optional<double> intersect_ray(const Segment& s, const Vec2& origin, const Vec2& dir);

/// True when the two closed segments share a point.
bool segments_intersect(const Segment& s, const Segment& t);

}  // namespace floornav
