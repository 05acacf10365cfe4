#include "floornav/planning/jump_point_search.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>

#include "best_first_search.hpp"

namespace floornav {
namespace {

/// Jump point search (Harabor and Grastien 2011) for octile moves without corner cutting (the
/// rules of PathFinding.js's JPFMoveDiagonallyIfNoObstacles): the same optimal octile length as
/// run_octile_astar, found by expanding only the jump points, where a straight run meets a
/// forced turn or a diagonal run sees one along its straight sub-runs. Same working memory and
/// open list; `expanded` counts the jump points expanded. The path is one of the optimal ones,
/// not necessarily run_octile_astar's (ties go another way), filled in cell by cell.
class JumpPoints {
 public:
  JumpPoints(const FreeRaster& raster, GridCell goal)
      : free_(raster.free.data()), w_(raster.width), h_(raster.height), goal_(goal) {}

  bool is_free(int x, int y) const {
    return x >= 0 && y >= 0 && x < w_ && y < h_ &&
           free_[static_cast<std::size_t>(y) * static_cast<std::size_t>(w_) +
                 static_cast<std::size_t>(x)] != 0;
  }

  /// The jump point reached from (x, y) by straight steps (dx, dy) (one of them 0), if any: the
  /// goal, or a cell with a forced neighbour (a side cell reachable, without cutting a corner,
  /// only through it: free, while the side cell behind it is blocked). A side row or column
  /// outside the raster has no cells to force.
  std::optional<GridCell> straight(int x, int y, int dx, int dy) const {
    const std::size_t w = static_cast<std::size_t>(w_);
    auto at = [&](int cx, int cy) {
      return free_ + static_cast<std::size_t>(cy) * w + static_cast<std::size_t>(cx);
    };
    if (dy == 0) {
      const std::uint8_t* row = at(0, y);
      const std::uint8_t* below = y > 0 ? row - w : nullptr;
      const std::uint8_t* above = y + 1 < h_ ? row + w : nullptr;
      const int goal_x = y == goal_.y ? goal_.x : -2;
      for (x += dx; x >= 0 && x < w_ && row[x]; x += dx) {
        if (x == goal_x) return GridCell{x, y};
        if ((below && below[x] && !below[x - dx]) || (above && above[x] && !above[x - dx]))
          return GridCell{x, y};
      }
      return std::nullopt;
    }
    const std::ptrdiff_t step = dy * static_cast<std::ptrdiff_t>(w);
    const bool left = x > 0, right = x + 1 < w_;
    const int goal_y = x == goal_.x ? goal_.y : -2;
    for (y += dy; y >= 0 && y < h_; y += dy) {
      const std::uint8_t* c = at(x, y);
      if (!*c) return std::nullopt;
      if (y == goal_y) return GridCell{x, y};
      if ((left && c[-1] && !c[-1 - step]) || (right && c[1] && !c[1 - step]))
        return GridCell{x, y};
    }
    return std::nullopt;
  }

  /// The jump point reached from (x, y) by diagonal steps (dx, dy), if any: the first cell of the
  /// run whose straight sub-runs find one.
  std::optional<GridCell> diagonal(int x, int y, int dx, int dy) const {
    for (;;) {
      if (!is_free(x + dx, y) || !is_free(x, y + dy) || !is_free(x + dx, y + dy))
        return std::nullopt;  // blocked, or a corner to cut
      x += dx;
      y += dy;
      if (x == goal_.x && y == goal_.y) return GridCell{x, y};
      if (straight(x, y, dx, 0) || straight(x, y, 0, dy)) return GridCell{x, y};
    }
  }

  /// The successors of jump point u at (ux, uy): the jump points straight and diagonal runs from
  /// it reach, in the directions worth searching: all at the start; else those a move in direction
  /// (dx, dy) from the parent leaves (natural and forced neighbours, pruned as JPS does).
  template <class Relax>
  void operator()(std::size_t, int ux, int uy, std::int32_t parent, Relax& relax) const {
    const std::size_t w = static_cast<std::size_t>(w_);
    auto relax_at = [&](const std::optional<GridCell>& j) {
      if (j)
        relax(static_cast<std::size_t>(j->y) * w + static_cast<std::size_t>(j->x), j->x - ux,
              j->y - uy, [&] { return octile_distance(j->x - ux, j->y - uy); });
    };
    int dx = 0, dy = 0;
    if (parent >= 0) {
      const std::size_t p = static_cast<std::size_t>(parent);
      dx = (ux > static_cast<int>(p % w)) - (ux < static_cast<int>(p % w));
      dy = (uy > static_cast<int>(p / w)) - (uy < static_cast<int>(p / w));
    }
    const bool all = dx == 0 && dy == 0;
    for (int ddy = -1; ddy <= 1; ++ddy)
      for (int ddx = -1; ddx <= 1; ++ddx) {
        if (ddx == 0 && ddy == 0) continue;
        if (!all) {
          // Diagonal arrival: its two straight parts and itself. Straight arrival: onwards, the
          // sides and the diagonals between onwards and a side.
          const bool keep = dx != 0 && dy != 0 ? (ddx == dx || ddx == 0) && (ddy == dy || ddy == 0)
                            : dx != 0          ? ddx != -dx
                                               : ddy != -dy;
          if (!keep) continue;
        }
        if (ddx != 0 && ddy != 0)
          relax_at(diagonal(ux, uy, ddx, ddy));
        else
          relax_at(straight(ux, uy, ddx, ddy));
      }
  }

 private:
  const std::uint8_t* free_;
  int w_, h_;
  GridCell goal_;
};

bool run_octile_jps(SearchBuffers& b, const FreeRaster& raster, GridCell start, GridCell goal,
                    GridPath& path, std::size_t& expanded) {
  return run_octile_search(b, raster, start, goal, JumpPoints(raster, goal), path, expanded);
}

}  // namespace

std::optional<GridPath> octile_jump_point_search(const FreeRaster& raster, GridCell start,
                                                 GridCell goal) {
  thread_local SearchBuffers buffers;
  GridPath path;
  std::size_t expanded = 0;
  if (!run_octile_jps(buffers, raster, start, goal, path, expanded)) return std::nullopt;
  return path;
}

}  // namespace floornav
