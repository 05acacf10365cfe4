#include "floornav/geometry/circle.hpp"

#include <cmath>

namespace floornav {

Vec2 nearest_point(const Circle& c, const Vec2& p) {
  const Vec2 d = p - c.center;
  const double n = d.norm();
  if (n <= 0.0) return c.center + Vec2(c.radius, 0.0);
  return c.center + d * (c.radius / n);
}

std::optional<double> intersect_ray(const Circle& c, const Vec2& origin, const Vec2& dir) {
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
