#pragma once
// Rasters and worlds the planning tests and the scenario optimum's tests share.

#include <array>
#include <cstddef>
#include <initializer_list>

#include "floornav/geometry/box2.hpp"
#include "floornav/planning/free_raster.hpp"
#include "floornav/world/world.hpp"

namespace floornav::test {

/// A width x height raster, all free but the listed cells.
inline FreeRaster raster(int width, int height, std::initializer_list<std::array<int, 2>> blocked) {
  FreeRaster r;
  r.width = width;
  r.height = height;
  r.free.assign(static_cast<std::size_t>(width) * height, 1);
  for (const auto& c : blocked) r.free[static_cast<std::size_t>(c[1]) * width + c[0]] = 0;
  return r;
}

/// Bounds 4 x 2 m; a wall at x in [1.9, 2.1] across, with an opening `gap` wide around y = 1.
inline World gap_world(double gap) {
  WorldDesc d;
  d.bounds = Box2{{0.0, 0.0}, {4.0, 2.0}};
  const double lo = 1.0 - gap / 2.0, hi = 1.0 + gap / 2.0;
  d.polygons = {{{1.9, 0.0}, {2.1, 0.0}, {2.1, lo}, {1.9, lo}},
                {{1.9, hi}, {2.1, hi}, {2.1, 2.0}, {1.9, 2.0}}};
  return World(d);
}

}  // namespace floornav::test
