#include "world_raster.hpp"

#include <algorithm>
#include <cmath>

#include "floornav/world/occupancy_grid.hpp"

namespace floornav {

namespace {
constexpr double kMaxCells = 1e6;  ///< a shape world's raster gets coarser beyond this
}  // namespace

WorldRaster world_raster(const World& world) {
  WorldRaster m;
  const auto cell_centre = [&](int ix, int iy) {
    return m.origin.transform_point(Vec2((ix + 0.5) * m.resolution, (iy + 0.5) * m.resolution));
  };
  if (const OccupancyGrid* g = world.grid()) {
    m.resolution = g->resolution();
    m.width = g->width();
    m.height = g->height();
    m.origin = g->origin();
    m.cells.resize(static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height));
    for (int iy = 0; iy < m.height; ++iy)
      for (int ix = 0; ix < m.width; ++ix)
        m.cells[static_cast<std::size_t>(iy) * m.width + ix] = g->unknown(ix, iy) ? std::int8_t{-1}
                                                               : g->occupied(ix, iy)
                                                                   ? std::int8_t{100}
                                                                   : 0;
    // Shapes over the map: only the cells of their boxes are tested.
    std::vector<Box2> boxes;
    for (const Circle& c : world.circles())
      boxes.push_back({c.center.array() - c.radius, c.center.array() + c.radius});
    for (const auto& poly : world.polygons()) {
      Box2 b{poly.front(), poly.front()};
      for (const Vec2& p : poly) {
        b.min = b.min.cwiseMin(p);
        b.max = b.max.cwiseMax(p);
      }
      boxes.push_back(b);
    }
    for (const Box2& b : boxes) {
      const Vec2 lo = rotate(b.min - m.origin.position, -m.origin.theta) / m.resolution;
      const Vec2 hi = rotate(b.max - m.origin.position, -m.origin.theta) / m.resolution;
      const int x0 = std::max(0, static_cast<int>(std::floor(std::min(lo.x(), hi.x()))));
      const int x1 = std::min(m.width - 1, static_cast<int>(std::ceil(std::max(lo.x(), hi.x()))));
      const int y0 = std::max(0, static_cast<int>(std::floor(std::min(lo.y(), hi.y()))));
      const int y1 = std::min(m.height - 1, static_cast<int>(std::ceil(std::max(lo.y(), hi.y()))));
      for (int iy = y0; iy <= y1; ++iy)
        for (int ix = x0; ix <= x1; ++ix)
          if (world.is_inside_obstacle(cell_centre(ix, iy)))
            m.cells[static_cast<std::size_t>(iy) * m.width + ix] = 100;
    }
    return m;
  }
  const Box2& extent = world.extent();
  const Vec2 size = extent.size();
  if (!(size.x() > 0.0 && size.y() > 0.0) || !size.allFinite()) {
    m.cells.assign(1, 0);
    return m;
  }
  while (std::ceil(size.x() / m.resolution) * std::ceil(size.y() / m.resolution) > kMaxCells)
    m.resolution *= 2.0;
  m.width = static_cast<int>(std::ceil(size.x() / m.resolution));
  m.height = static_cast<int>(std::ceil(size.y() / m.resolution));
  m.origin = {extent.min, 0.0};
  m.cells.resize(static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height));
  for (int iy = 0; iy < m.height; ++iy)
    for (int ix = 0; ix < m.width; ++ix)
      m.cells[static_cast<std::size_t>(iy) * m.width + ix] =
          world.is_inside_obstacle(cell_centre(ix, iy)) ? std::int8_t{100} : 0;
  return m;
}

}  // namespace floornav
