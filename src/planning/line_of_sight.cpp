#include "floornav/planning/line_of_sight.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

namespace floornav {

bool line_of_sight(const FreeRaster& raster, const Vec2& a, const Vec2& b) {
  if (!is_finite(a) || !is_finite(b)) return false;
  constexpr double kEps = 1e-9;  // a touch of a border or corner counts (conservative)
  const Vec2 lo = a.x() <= b.x() ? a : b;
  const Vec2 hi = a.x() <= b.x() ? b : a;
  const double dx = hi.x() - lo.x();
  const int x0 = static_cast<int>(std::floor(lo.x() - kEps));
  const int x1 = static_cast<int>(std::floor(hi.x() + kEps));
  const double slope = dx > 0.0 ? (hi.y() - lo.y()) / dx : 0.0;
  // Inside the raster (the segment's columns, and its rows widened by a whole cell, far above
  // any rounding of the rows below), the cells are read without bounds checks: the same cells.
  const bool inside = x0 >= 0 && x1 < raster.width && std::min(lo.y(), hi.y()) >= 1.0 &&
                      std::max(lo.y(), hi.y()) + 1.0 < raster.height;
  const std::size_t w = static_cast<std::size_t>(std::max(raster.width, 0));
  for (int ix = x0; ix <= x1; ++ix) {
    // The part of the segment within column ix (widened by kEps), then the rows it spans.
    const double xa = std::max(lo.x(), ix - kEps), xb = std::min(hi.x(), ix + 1 + kEps);
    double ya = lo.y(), yb = hi.y();
    if (dx > 0.0) {
      ya = lo.y() + slope * (xa - lo.x());
      yb = lo.y() + slope * (xb - lo.x());
    }
    if (ya > yb) std::swap(ya, yb);
    const int y0 = static_cast<int>(std::floor(ya - kEps));
    const int y1 = static_cast<int>(std::floor(yb + kEps));
    if (inside) {
      const std::uint8_t* c = raster.free.data() + static_cast<std::size_t>(ix);
      for (int iy = y0; iy <= y1; ++iy)
        if (!c[static_cast<std::size_t>(iy) * w]) return false;
      continue;
    }
    for (int iy = y0; iy <= y1; ++iy)
      if (!raster.is_free(ix, iy)) return false;
  }
  return true;
}

}  // namespace floornav
