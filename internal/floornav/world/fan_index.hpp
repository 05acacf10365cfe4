#pragma once
/// @file
/// OccupancyGrid::FanIndex: what OccupancyGrid::cast_fan tests, built with the grid
/// (grid_fan.cpp's compute_boundary) and read by its fans and their tests.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "floornav/world/occupancy_grid.hpp"

namespace floornav {

struct OccupancyGrid::FanIndex {
  /// The side (cells) of the square tiles the runs are kept by: tiles wholly beyond every beam's
  /// hit so far are passed over.
  static constexpr int kTile = 64;

  /// A run of occupied cells whose neighbour on one side is free (a free cell of the grid or
  /// outside it): side 0 (x - 1) and 1 (x + 1) as runs of rows in a column, side 2 (y - 1) and 3
  /// (y + 1) as runs of columns in a row. A walk enters or touches an occupied cell first only
  /// from a free neighbour on a side facing its origin.
  struct Run {
    std::int32_t line;   ///< the column (sides 0, 1) or row (sides 2, 3)
    std::int32_t first;  ///< along the line
    std::int32_t last;   ///< inclusive
    /// The free component (free_component) whose walks can touch the run's cells first.
    std::int32_t component;
    /// For a run of one cell: bit s set when a run of side s (perpendicular, same component)
    /// has this cell at its end on this run's face, and tests the cell for it: a fan from an
    /// origin that run faces leaves this one out (grid_fan.cpp).
    std::int32_t cover{0};
  };
  /// The cells a tile's runs cover: [x0, x1) x [y0, y1) (empty for a tile without runs).
  struct CellBox {
    std::int32_t x0, x1, y0, y1;
  };

  /// For each free cell, its 4-connected component of free cells (0: the one outside the grid,
  /// which counts as free, and those touching it); -1 for an occupied cell. A fan from a
  /// component takes only the runs its walks can touch first.
  std::vector<std::int32_t> free_component;
  int tile_cols{0};
  int tile_rows{0};
  /// The runs cut at tile borders and kept tile by tile: tile t (row-major, tile_cols per row)
  /// has the runs runs[start[4 t + s] .. start[4 t + s + 1]) of side s, in component order.
  std::vector<Run> runs;
  std::vector<std::int32_t> start;
  /// For each tile, the cells its runs cover: a fan asks whether a beam may still reach this box
  /// rather than the whole tile.
  std::vector<CellBox> box;

  /// How many runs there are, and how many are one cell long and left out of a fan wherever a
  /// perpendicular run ending at that cell faces its origin too.
  struct RunCounts {
    std::size_t runs{0};
    std::size_t covered{0};
  };
  RunCounts run_counts() const {
    RunCounts c{runs.size(), 0};
    for (const Run& r : runs) c.covered += r.cover != 0 ? 1 : 0;
    return c;
  }
};

}  // namespace floornav
