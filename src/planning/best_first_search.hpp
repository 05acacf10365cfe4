#pragma once
// The best-first search both octile searches share (octile_astar.cpp, jump_point_search.cpp):
// per-cell state marked by a search count, the radix-heap open list, the path filled in cell by
// cell.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "floornav/planning/free_raster.hpp"
#include "open_list.hpp"

// In an unnamed namespace, as when they lived in one file: each search's file gets its own copy,
// with internal linkage, so that the compiler inlines them as before (BM_FloorOptimumAstar).
namespace floornav {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;

double octile_distance(int dx, int dy) {
  const int ax = std::abs(dx), ay = std::abs(dy);
  const int lo = std::min(ax, ay), hi = std::max(ax, ay);
  return (hi - lo) + kSqrt2 * lo;
}

/// What a search knows of one cell, in one place (the search reads and writes them together:
/// one cache line instead of three arrays). `mark` says what this search knows of the cell:
/// 2 * search + 1 closed, 2 * search open (g and parent valid), anything else untouched, so
/// nothing is cleared between searches.
struct CellState {
  double g;
  std::int32_t parent;
  std::uint32_t mark;
};
static_assert(sizeof(CellState) == 16);

/// A* working memory, kept per thread so that a search allocates nothing once the thread's
/// buffers fit its raster (a batch runs thousands).
struct SearchBuffers {
  std::vector<CellState> cells;
  OpenList open;
  std::uint32_t search{0};

  void begin(std::size_t n) {
    if (cells.size() < n || search >= 0x7FFFFFFEu) {
      cells.assign(std::max(n, cells.size()),
                   CellState{std::numeric_limits<double>::infinity(), -1, 0});
      search = 0;
    }
    ++search;
    open.clear();
  }
};

/// The best-first search both octile searches share (speed's radix-heap open list, marks instead of
/// clearing) into `path` with the working memory `b`: each expanded cell u at (ux, uy), `parent`
/// its parent's index (-1 at the start), is handed to `successors(u, ux, uy, parent, relax)`, which
/// calls `relax(v, dx, dy, step)` for each cell v = (ux + dx, uy + dy) reached from u by a move of
/// octile length `step()` (asked only of a cell not closed yet). `expanded` counts the cells
/// expanded. The path is the cells from start to goal, each parent to child run filled in cell by
/// cell (A*'s parents are neighbours: nothing to fill). False, with `path` empty, when the start or
/// the goal is blocked or no path joins them.
template <class Successors>
bool run_octile_search(SearchBuffers& b, const FreeRaster& raster, GridCell start, GridCell goal,
                       const Successors successors, GridPath& path, std::size_t& expanded) {
  path.length = 0.0;
  path.cells.clear();
  expanded = 0;
  if (!raster.is_free(start.x, start.y) || !raster.is_free(goal.x, goal.y)) return false;
  const std::size_t w = static_cast<std::size_t>(raster.width);
  b.begin(w * static_cast<std::size_t>(raster.height));
  const std::uint32_t open_mark = 2 * b.search, closed_mark = open_mark + 1;
  CellState* cell = b.cells.data();
  auto index = [w](int x, int y) {
    return static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
  };
  const std::size_t s = index(start.x, start.y), t = index(goal.x, goal.y);
  cell[s] = {0.0, -1, open_mark};
  b.open.push(
      {octile_distance(goal.x - start.x, goal.y - start.y), -0.0, static_cast<std::uint32_t>(s)});
  while (!b.open.empty()) {
    const std::size_t u = b.open.pop().index;
    if (cell[u].mark == closed_mark) continue;
    cell[u].mark = closed_mark;
    ++expanded;
    if (u == t) break;
    const int ux = static_cast<int>(u % w), uy = static_cast<int>(u / w);
    const int hx = goal.x - ux, hy = goal.y - uy;  // the heuristic's offsets from u
    const double gu = cell[u].g;
    auto relax = [&](std::size_t v, int dx, int dy, auto step) __attribute__((always_inline)) {
      CellState& cv = cell[v];
      const std::uint32_t m = cv.mark;
      if (m == closed_mark) return;
      const double gv = gu + step();
      if (m != open_mark || gv < cv.g) {
        cv = {gv, static_cast<std::int32_t>(u), open_mark};
        b.open.push({gv + octile_distance(hx - dx, hy - dy), -gv, static_cast<std::uint32_t>(v)});
      }
    };
    successors(u, ux, uy, cell[u].parent, relax);
  }
  if (cell[t].mark != closed_mark) return false;
  path.length = cell[t].g;
  // Goal first, then every cell between each cell and its parent (a straight or a diagonal run).
  for (std::int64_t v = static_cast<std::int64_t>(t); v >= 0;) {
    const int vx = static_cast<int>(static_cast<std::size_t>(v) % w);
    const int vy = static_cast<int>(static_cast<std::size_t>(v) / w);
    path.cells.push_back({vx, vy});
    const std::int32_t p = cell[static_cast<std::size_t>(v)].parent;
    if (p >= 0) {
      const int px = static_cast<int>(static_cast<std::size_t>(p) % w);
      const int py = static_cast<int>(static_cast<std::size_t>(p) / w);
      const int sx = (px > vx) - (px < vx), sy = (py > vy) - (py < vy);
      for (int x = vx + sx, y = vy + sy; x != px || y != py; x += sx, y += sy)
        path.cells.push_back({x, y});
    }
    v = p;
  }
  std::reverse(path.cells.begin(), path.cells.end());
  return true;
}

}  // namespace
}  // namespace floornav
