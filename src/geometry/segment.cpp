#include "floornav/geometry/segment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "floornav/geometry/ray.hpp"

namespace floornav {

double ray_collinear_segment_hit(const Vec2& origin, const Vec2& dir, const Vec2& a, const Vec2& b,
                                 double best) {
  const Vec2 w = a - origin;
  if (std::abs(cross(w, dir)) > 1e-12) return best;  // parallel, not on the line
  const double ta = w.dot(dir);
  const double tb = (b - origin).dot(dir);
  if (ta < 0.0 && tb < 0.0) return best;                           // behind
  const double t = ta < 0.0 || tb < 0.0 ? 0.0 : std::min(ta, tb);  // 0: origin on the segment
  return t < best ? t : best;
}

std::optional<double> intersect_ray(const Segment& s, const Vec2& origin, const Vec2& dir) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const double t = ray_segment_hit(origin, dir, s.a, s.b, s.b - s.a, kNone);
  if (t == kNone) return std::nullopt;
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
