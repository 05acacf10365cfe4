#pragma once
/// @file
/// Line segments: nearest point, distance, and ray intersection.

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
Vec2 nearest_point(const Segment& s, const Vec2& p);

/// Euclidean distance from `p` to segment `s`.
double distance(const Segment& s, const Vec2& p);

/// Distance along the ray `origin + t dir` (`dir` a unit vector) to where it first meets `s`,
/// if it does with `t >= 0`. A ray lying along the segment meets it at its nearer end.
/// (`ray_segment_hit` of ray.hpp, the form the casts use.)
std::optional<double> intersect_ray(const Segment& s, const Vec2& origin, const Vec2& dir);

/// True when the two closed segments share a point.
bool segments_intersect(const Segment& s, const Segment& t);

}  // namespace floornav
