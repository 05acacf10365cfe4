#include "floornav/geometry/segment.hpp"

#include <algorithm>
#include <cmath>

namespace floornav {

Vec2 nearest_point(const Segment& s, const Vec2& p) {
  const Vec2 d = s.b - s.a;
  const double len2 = d.squaredNorm();
  if (len2 <= 0.0) return s.a;
  const double t = std::clamp((p - s.a).dot(d) / len2, 0.0, 1.0);
  return s.a + t * d;
}

double distance(const Segment& s, const Vec2& p) {
  return (p - nearest_point(s, p)).norm();
}

std::optional<double> intersect_ray(const Segment& s, const Vec2& origin, const Vec2& dir) {
  const Vec2 e = s.b - s.a;
  const Vec2 w = s.a - origin;
  const double denom = cross(dir, e);
  if (std::abs(denom) < 1e-15) {
    // Parallel. Only a collinear segment ahead of the origin is hit, at its nearer end.
    if (std::abs(cross(w, dir)) > 1e-12) return std::nullopt;
    const double ta = w.dot(dir);
    const double tb = (s.b - origin).dot(dir);
    if (ta < 0.0 && tb < 0.0) return std::nullopt;
    if (ta < 0.0 || tb < 0.0) return 0.0;  // origin lies on the segment
    return std::min(ta, tb);
  }
  const double t = cross(w, e) / denom;    // along the ray
  const double u = cross(w, dir) / denom;  // along the segment, 0..1
  if (t < 0.0 || u < 0.0 || u > 1.0) return std::nullopt;
  return t;
}

namespace {
int orientation(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double v = cross(b - a, c - a);
  return (v > 0.0) - (v < 0.0);
}
bool on_segment(const Vec2& a, const Vec2& b, const Vec2& p) {
  return std::min(a.x(), b.x()) <= p.x() && p.x() <= std::max(a.x(), b.x()) &&
         std::min(a.y(), b.y()) <= p.y() && p.y() <= std::max(a.y(), b.y());
}
}  // namespace

bool segments_intersect(const Segment& s, const Segment& t) {
  const int o1 = orientation(s.a, s.b, t.a);
  const int o2 = orientation(s.a, s.b, t.b);
  const int o3 = orientation(t.a, t.b, s.a);
  const int o4 = orientation(t.a, t.b, s.b);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && on_segment(s.a, s.b, t.a)) return true;
  if (o2 == 0 && on_segment(s.a, s.b, t.b)) return true;
  if (o3 == 0 && on_segment(t.a, t.b, s.a)) return true;
  if (o4 == 0 && on_segment(t.a, t.b, s.b)) return true;
  return false;
}

}  // namespace floornav
