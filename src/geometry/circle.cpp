#include "floornav/geometry/circle.hpp"

#include <cmath>

namespace floornav {

Vec2 nearest_point(const Circle& c, const Vec2& p) {
  const Vec2 d = p - c.center;
  const double n = d.norm();
  if (n <= 0.0) return c.center + Vec2(c.radius, 0.0);
  return c.center + d * (c.radius / n);
}

}  // namespace floornav
