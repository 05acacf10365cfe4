#include "floornav/geometry/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace floornav {

double signed_area(std::span<const Vec2> v) {
  double twice = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) twice += cross(v[i], v[(i + 1) % v.size()]);
  return 0.5 * twice;
}

bool is_convex(std::span<const Vec2> v) {
  if (v.size() < 3) return false;
  int sign = 0;
  const std::size_t n = v.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double turn = cross(v[(i + 1) % n] - v[i], v[(i + 2) % n] - v[(i + 1) % n]);
    const int s = (turn > 1e-12) - (turn < -1e-12);
    if (s == 0) continue;
    if (sign == 0) sign = s;
    if (s != sign) return false;
  }
  // All turns one way is not enough for a polygon that winds twice (a pentagram): its angles sum
  // to 4 pi. A simple polygon whose turns agree is convex.
  return sign != 0 && is_simple(v);
}

bool is_simple(std::span<const Vec2> v) {
  const std::size_t n = v.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    if ((v[(i + 1) % n] - v[i]).squaredNorm() <= 0.0) return false;
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) continue;
      if (segments_intersect(edge(v, i), edge(v, j))) return false;
    }
  }
  return std::abs(signed_area(v)) > 0.0;
}

bool contains(std::span<const Vec2> v, const Vec2& p) {
  bool inside = false;
  const std::size_t n = v.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Vec2& a = v[i];
    const Vec2& b = v[j];
    if (distance(Segment{a, b}, p) <= 1e-12) return true;
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x_cross = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x_cross) inside = !inside;
    }
  }
  return inside;
}

double boundary_distance(std::span<const Vec2> v, const Vec2& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i) best = std::min(best, distance(edge(v, i), p));
  return best;
}

std::vector<Vec2> make_rectangle(const Vec2& center, const Vec2& size, double angle) {
  const Vec2 h = 0.5 * size;
  const Vec2 corners[4] = {{-h.x(), -h.y()}, {h.x(), -h.y()}, {h.x(), h.y()}, {-h.x(), h.y()}};
  std::vector<Vec2> out;
  out.reserve(4);
  for (const Vec2& c : corners) out.push_back(center + rotate(c, angle));
  return out;
}

}  // namespace floornav
