#include "floornav/geometry/oriented_box.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace floornav {

OrientedBox OrientedBox::make(const Vec2& center, const Vec2& size, double heading) {
  return {center, 0.5 * size, Vec2(std::cos(heading), std::sin(heading))};
}

std::array<Vec2, 4> OrientedBox::corners() const {
  const Vec2 along = half.x() * axis, across = half.y() * rotate_ccw90(axis);
  return {center - along - across, center + along - across, center + along + across,
          center - along + across};
}

double signed_distance(const OrientedBox& b, const Vec2& p) {
  const Vec2 q = b.to_local(p);
  const Vec2 d(std::abs(q.x()) - b.half.x(), std::abs(q.y()) - b.half.y());
  const double outside = d.cwiseMax(0.0).norm();
  return outside > 0.0 ? outside : std::max(d.x(), d.y());
}

std::optional<double> intersect_ray(const OrientedBox& b, const Vec2& origin, const Vec2& dir) {
  const Vec2 o = b.to_local(origin);
  const Vec2 d(dir.dot(b.axis), cross(b.axis, dir));
  double t_in = 0.0, t_out = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    const double h = b.half[k];
    if (d[k] == 0.0) {
      if (std::abs(o[k]) > h) return std::nullopt;  // parallel to the slab, outside it
      continue;
    }
    double t0 = (-h - o[k]) / d[k], t1 = (h - o[k]) / d[k];
    if (t0 > t1) std::swap(t0, t1);
    t_in = std::max(t_in, t0);
    t_out = std::min(t_out, t1);
    if (t_in > t_out) return std::nullopt;
  }
  return t_in;
}

}  // namespace floornav
