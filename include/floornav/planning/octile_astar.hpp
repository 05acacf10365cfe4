#pragma once
/// @file
/// Octile A* on a FreeRaster: 8-connected moves, no corner cutting, deterministic.

#include <cstddef>
#include <memory>
#include <optional>

#include "floornav/planning/free_raster.hpp"

namespace floornav {

/// Octile A* from `start` to `goal`: moves to the 8 neighbours, a diagonal move only when both
/// cells it passes between are free (no corner cutting). Empty when either cell is blocked or
/// outside the raster, or the goal is unreachable. Deterministic; iterative; O(n log n).
/// (The search of GridSearch, with working memory kept per thread.)
std::optional<GridPath> octile_astar(const FreeRaster& raster, GridCell start, GridCell goal);

/// The octile A* of `octile_astar` with its working memory (costs, parents, open list) kept from
/// one search to the next: a planner that searches again and again on rasters of one size
/// allocates nothing after its first search (the cells of the path aside). Entries are
/// invalidated by a search count, not by clearing the buffers; the open list is a radix heap.
class GridSearch {
 public:
  GridSearch();
  ~GridSearch();
  GridSearch(GridSearch&&) noexcept;
  GridSearch& operator=(GridSearch&&) noexcept;

  /// The same path as `octile_astar(raster, start, goal)`, into `path` (its cells vector is
  /// reused). False, with `path` empty, when there is none.
  bool search(const FreeRaster& raster, GridCell start, GridCell goal, GridPath& path);
  /// Cells expanded by the last search (for benchmarks and tests).
  std::size_t expanded() const { return expanded_; }

 private:
  struct Buffers;  // the A* working memory (octile_astar.cpp), reused by every search
  std::unique_ptr<Buffers> buffers_;
  std::size_t expanded_{0};
};

}  // namespace floornav
