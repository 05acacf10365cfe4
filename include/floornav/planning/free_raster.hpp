#pragma once
/// @file
/// The raster the planners search: free and blocked cells, a cell, a path of cells, and the free
/// cell nearest to a point.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// A grid of free (nonzero) and blocked (zero) cells, row-major from row iy = 0. In cell units,
/// cell (ix, iy) covers [ix, ix + 1) x [iy, iy + 1) and its centre is (ix + 0.5, iy + 0.5).
struct FreeRaster {
  int width{0};
  int height{0};
  std::vector<std::uint8_t> free;  ///< width * height bytes

  bool is_free(int ix, int iy) const {
    return ix >= 0 && iy >= 0 && ix < width && iy < height &&
           free[static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) +
                static_cast<std::size_t>(ix)] != 0;
  }
};

struct GridCell {
  int x{0};
  int y{0};
  bool operator==(const GridCell&) const = default;
};

struct GridPath {
  double length{0.0};           ///< in cells: 1 per straight step, sqrt(2) per diagonal step
  std::vector<GridCell> cells;  ///< start to goal, both included
};

/// The free cell whose centre is nearest to `p` (cell units) within `radius` cells (`p`'s own cell
/// when it is free), ties to the lowest row then column; nullopt when there is none.
std::optional<GridCell> snap_to_free(const FreeRaster& raster, const Vec2& p, double radius);

}  // namespace floornav
