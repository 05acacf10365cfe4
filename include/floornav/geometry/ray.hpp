#pragma once
/// @file
/// Rays against shapes: the one box clip and the one segment and disc hit tests of the library.
/// World's spatial index, its fan and its brute-force oracle, and OccupancyGrid's walks all use
/// these, so that every cast agrees with every other one to the bit.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "floornav/geometry/box2.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// Clips the part `[t_enter, t_exit]` of the ray `origin + t dir` to `box` (the slab method,
/// Kay & Kajiya 1986): narrows the interval to where the ray is inside the box, and returns false
/// when nothing is left. A ray parallel to an axis (that component exactly 0) misses unless its
/// origin lies in `[min, max)` on that axis, as a cell `[i, i + 1)` holds its lower edge only.
inline bool clip_ray_to_box(const Vec2& origin, const Vec2& dir, const Box2& box, double& t_enter,
                            double& t_exit) {
  for (int a = 0; a < 2; ++a) {
    if (dir[a] == 0.0) {
      if (!(origin[a] >= box.min[a] && origin[a] < box.max[a])) return false;
      continue;
    }
    double t0 = (box.min[a] - origin[a]) / dir[a];
    double t1 = (box.max[a] - origin[a]) / dir[a];
    if (t0 > t1) std::swap(t0, t1);
    t_enter = std::max(t_enter, t0);
    t_exit = std::min(t_exit, t1);
  }
  return !(t_enter > t_exit);
}

/// `ray_segment_hit` for a ray parallel to the segment: it meets it only when collinear, at the
/// nearer end (0 when the origin lies on the segment).
double ray_collinear_segment_hit(const Vec2& origin, const Vec2& dir, const Vec2& a, const Vec2& b,
                                 double best);

/// How far past its ends a segment is hit, as a fraction of its length: a ray through a vertex
/// meets at least one of its two edges however the along-segment positions round (a solid's
/// edges seen from its solid side are never tested, so the other edge may not be there to catch
/// it). 1e-9 of a 1 m edge is a nanometre.
inline constexpr double kSegmentEndSlack = 1e-9;

/// The ray `origin + t dir` (t >= 0, `dir` a unit vector) against the segment from `a` to `b`,
/// whose edge `e = b - a` the caller computes once: the distance t where they meet when it is
/// below `best`, else `best` (so a NaN counts as no hit). The segment reaches kSegmentEndSlack
/// past each end. The along-segment division is only paid for a hit nearer than `best`, and `b`
/// is only read for a ray parallel to the segment.
inline double ray_segment_hit(const Vec2& origin, const Vec2& dir, const Vec2& a, const Vec2& b,
                              const Vec2& e, double best) {
  const Vec2 w = a - origin;
  const double denom = cross(dir, e);
  if (std::abs(denom) < 1e-15) return ray_collinear_segment_hit(origin, dir, a, b, best);
  const double t = cross(w, e) / denom;      // along the ray
  if (!(t >= 0.0 && t < best)) return best;  // behind, no nearer, or NaN
  const double u = cross(w, dir) / denom;    // along the segment, 0..1
  if (u < -kSegmentEndSlack || u > 1.0 + kSegmentEndSlack) return best;
  return t;
}

/// Whether a segment (from `a`, edge `e`, `pa` = a - origin) whose solid side is `side` (+1 the
/// left of a -> b, -1 the right, 0 unknown) is seen from that side by the origin. A ray from a
/// point outside a closed solid first meets it on an edge seen from the free side (or at a vertex
/// it shares with one), so such edges need no ray test; an origin on the edge's line sees it
/// from neither side.
inline bool seen_from_solid_side(double side, const Vec2& pa, const Vec2& e) {
  return side * cross(pa, e) > 0.0;
}

/// The ray `origin + t dir` (t >= 0, `dir` a unit vector) against the solid disc `c`: the
/// distance t to its boundary (0 when the origin is inside) when it is below `best`, else `best`
/// (a NaN counts as no hit). Its three tests (the origin inside, the disc behind, the line
/// missing it) are combined without a branch: the one branch left is taken only when the ray
/// meets the disc's line ahead (a ray misses most discs it is tested against, and those tests
/// went either way).
inline double ray_circle_hit(const Vec2& origin, const Vec2& dir, const Circle& c, double best) {
  const Vec2 m = origin - c.center;
  const double cc = m.squaredNorm() - c.radius * c.radius;
  const double b = m.dot(dir);
  const double disc = b * b - cc;
  const unsigned inside = cc <= 0.0;
  const unsigned ahead = static_cast<unsigned>(b <= 0.0) & static_cast<unsigned>(disc >= 0.0);
  if ((inside | ahead) == 0) return best;
  const double t = inside ? 0.0 : -b - std::sqrt(disc);
  return t < best ? t : best;
}

/// `ray_circle_hit` without a bound: the distance to the disc's boundary (0 from inside), or none
/// when the ray misses it.
inline std::optional<double> intersect_ray(const Circle& c, const Vec2& origin, const Vec2& dir) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const double t = ray_circle_hit(origin, dir, c, kNone);
  return t < kNone ? std::optional<double>(t) : std::nullopt;
}

}  // namespace floornav
