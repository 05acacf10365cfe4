#include "floornav/planning/raster_frame.hpp"

#include <algorithm>
#include <cmath>

#include "floornav/geometry/box2.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

/// The frame of the raster for `world`, or nullopt when it would be too large.
std::optional<RasterFrame> choose_frame(const World& world, double r, const Vec2& start,
                                        std::span<const Vec2> goals, const RasterOptions& options) {
  RasterFrame f;
  if (const OccupancyGrid* g = world.grid()) {
    f.origin = g->origin();
    f.cell = g->resolution();
    f.width = g->width();
    f.height = g->height();
    if (static_cast<double>(f.width) * f.height > static_cast<double>(options.max_cells))
      return std::nullopt;
    return f;
  }
  Box2 box;
  if (world.bounds()) {
    box = *world.bounds();
  } else {
    box.min = box.max = start;
    auto grow = [&](const Vec2& p) {
      box.min = box.min.cwiseMin(p);
      box.max = box.max.cwiseMax(p);
    };
    for (const Vec2& g : goals) grow(g);
    const Box2& e = world.extent();
    if (e.max.x() > e.min.x() || e.max.y() > e.min.y()) {
      grow(e.min);
      grow(e.max);
    }
  }
  double cell = options.cell_finer_than_radius
                    ? std::min(options.cell_size, r > 0.0 ? r / 2.0 : options.cell_size)
                    : options.cell_size;
  // Outside unbounded worlds, a margin so that the path can go round the outermost obstacles.
  auto padded = [&](double c) -> Vec2 {
    const double m = world.bounds() ? 0.0 : r + 4.0 * c;
    return box.size() + Vec2(2.0 * m, 2.0 * m);
  };
  const Vec2 first = padded(cell);
  const double cells = (first.x() / cell + 1.0) * (first.y() / cell + 1.0);
  if (cells > static_cast<double>(options.max_cells)) {
    cell *= std::sqrt(cells / static_cast<double>(options.max_cells)) * 1.01;
    // Cells coarser than the robot's radius cannot resolve the gaps it fits through.
    if (cell > std::max(r, options.cell_size)) return std::nullopt;
  }
  const double m = world.bounds() ? 0.0 : r + 4.0 * cell;
  const Vec2 size = padded(cell);
  f.origin = Pose2{box.min - Vec2(m, m), 0.0};
  f.cell = cell;
  f.width = std::max(1, static_cast<int>(std::ceil(size.x() / cell)));
  f.height = std::max(1, static_cast<int>(std::ceil(size.y() / cell)));
  if (static_cast<double>(f.width) * f.height > static_cast<double>(options.max_cells))
    return std::nullopt;
  return f;
}

}  // namespace

std::optional<RasterFrame> choose_raster_frame(const World& world, double body_radius,
                                               const Vec2& start, std::span<const Vec2> goals,
                                               const RasterOptions& options) {
  if (!is_finite(start) || !std::isfinite(body_radius) || body_radius < 0.0 ||
      !(options.cell_size > 0.0))
    return std::nullopt;
  return choose_frame(world, body_radius, start, goals, options);
}

}  // namespace floornav
