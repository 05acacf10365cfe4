#include "floornav/planning/free_raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace floornav {

std::optional<GridCell> snap_to_free(const FreeRaster& raster, const Vec2& p, double radius) {
  const int cx = static_cast<int>(std::floor(std::clamp(p.x(), -1e9, 1e9)));
  const int cy = static_cast<int>(std::floor(std::clamp(p.y(), -1e9, 1e9)));
  if (raster.is_free(cx, cy)) return GridCell{cx, cy};
  const int reach = static_cast<int>(std::ceil(radius));
  std::optional<GridCell> best;
  double best_d = std::numeric_limits<double>::infinity();
  for (int y = std::max(0, cy - reach); y <= std::min(raster.height - 1, cy + reach); ++y)
    for (int x = std::max(0, cx - reach); x <= std::min(raster.width - 1, cx + reach); ++x) {
      if (!raster.is_free(x, y)) continue;
      const double d = (Vec2(x + 0.5, y + 0.5) - p).norm();
      if (d <= radius + 0.5 && d < best_d) best_d = d, best = GridCell{x, y};
    }
  return best;
}

}  // namespace floornav
