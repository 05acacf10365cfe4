#include <algorithm>
#include <cmath>

#include "cell_index.hpp"
#include "floornav/geometry/ray.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "grid_walk.hpp"

// OccupancyGrid's ray walk: the cells a ray crosses, in order (Amanatides & Woo), exactly, with
// jumps over free space by the distance transform's free runs.

namespace floornav {

using cell_detail::clamp_cell;
using grid_detail::BoundaryTimes;
using grid_detail::kFreeRunUnits;
using grid_detail::kInf;
using grid_detail::kMinJump;

double OccupancyGrid::cast_ray(const Vec2& origin_world, const Vec2& dir, double max_range) const {
  return cast(origin_world, dir, max_range, true);
}

double OccupancyGrid::cast_ray_cell_by_cell(const Vec2& origin_world, const Vec2& dir,
                                            double max_range) const {
  return cast(origin_world, dir, max_range, false);
}

double OccupancyGrid::cast(const Vec2& origin_world, const Vec2& dir, double max_range,
                           bool skip) const {
  // Everything below is in cell units of the grid frame: cell (ix, iy) is [ix, ix+1) x [iy, iy+1).
  const Vec2 o = to_grid(origin_world) / resolution_;
  const Vec2 d(cos_yaw_ * dir.x() + sin_yaw_ * dir.y(), -sin_yaw_ * dir.x() + cos_yaw_ * dir.y());
  if (!is_finite(o) || !is_finite(d) || !(max_range >= 0.0)) return max_range;
  const double t_max = max_range / resolution_;

  // Clip the ray to the grid's box (slab method); a ray that starts inside keeps t0 = 0 (so with
  // `skip` such a ray does not clip: nothing else of the clipping is used).
  double t0 = 0.0;
  double t1 = t_max;
  const bool inside = o.x() >= 0.0 && o.x() < width_ && o.y() >= 0.0 && o.y() < height_;
  const Box2 cells{Vec2(0.0, 0.0), Vec2(width_, height_)};
  if (!(skip && inside) && !clip_ray_to_box(o, d, cells, t0, t1)) return max_range;

  int ix = clamp_cell(t0 > 0.0 ? o.x() + t0 * d.x() : o.x(), width_);
  int iy = clamp_cell(t0 > 0.0 ? o.y() + t0 * d.y() : o.y(), height_);
  const int sx = d.x() > 0.0 ? 1 : (d.x() < 0.0 ? -1 : 0);
  const int sy = d.y() > 0.0 ? 1 : (d.y() < 0.0 ? -1 : 0);
  // The times the walk leaves column i and row i (grid_walk.hpp).
  const BoundaryTimes column{o.x(), d.x(), sx}, row{o.y(), d.y(), sy};
  // Jumps need a direction of length <= 1 (a unit `dir`) and no component so tiny that 1 / d
  // overflows; anything else takes the cell-by-cell walk.
  const bool jumps = skip && (sx != 0 || sy != 0) && d.squaredNorm() <= 1.0 + 1e-9 &&
                     (sx == 0 || std::abs(d.x()) >= 1e-290) &&
                     (sy == 0 || std::abs(d.y()) >= 1e-290);
  if (jumps) return walk_with_jumps(o, d, max_range, t_max, t0, ix, iy);
  double t = t0;
  for (;;) {
    if (occupied_[static_cast<std::size_t>(iy) * width_ + ix] != 0) {
      return std::min(t * resolution_, max_range);
    }
    const double tx = column.exit(ix);
    const double ty = row.exit(iy);
    const double tn = std::max(t, std::min(tx, ty));
    if (!(tn <= t_max) || tn == kInf) return max_range;
    if (tx < ty) {
      ix += sx;
    } else if (ty < tx) {
      iy += sy;
    } else {
      // Through a corner: the two cells that share it are touched too (closed squares).
      if (occupied(ix + sx, iy) || occupied(ix, iy + sy)) {
        return std::min(tn * resolution_, max_range);
      }
      ix += sx;
      iy += sy;
    }
    t = tn;
    if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return max_range;
  }
}

double OccupancyGrid::walk_with_jumps(const Vec2& o, const Vec2& d, double max_range, double t_max,
                                      double t0, int ix, int iy) const {
  // The walk above, to the same bits, with two changes.
  //
  // 1. It jumps over free space. A ray entering cell c runs free_run_[c] / 16 cells before it can
  //    touch an occupied square, so every cell it touches before t + run is free. The walk takes
  //    the boundary events (exit_x of successive columns, exit_y of successive rows; each list
  //    increasing) in increasing order, a tie being a corner step. So after all events before
  //    `target` it is in the first column jx with exit_x(jx) >= target, and likewise the row:
  //    that is where a jump lands.
  // 2. It decides with products by 1 / d instead of quotients by d, which differ from the
  //    quotients by a few ulps (kRel covers them a thousandfold); a decision too close to call is
  //    made with the quotients. The entry time of a cell is the latest event before it, that is
  //    the larger of exit_x of the previous column and exit_y of the previous row (or t0), so
  //    the exact time is only computed where it is returned or compared to t_max closely.
  constexpr double kRel = 1e-13;
  const int sx = d.x() > 0.0 ? 1 : (d.x() < 0.0 ? -1 : 0);
  const int sy = d.y() > 0.0 ? 1 : (d.y() < 0.0 ? -1 : 0);
  const BoundaryTimes column{o.x(), d.x(), sx}, row{o.y(), d.y(), sy};
  const auto exit_x = [&](int i) { return column.exit(i); };
  const auto exit_y = [&](int i) { return row.exit(i); };
  const double inv_x = sx != 0 ? 1.0 / d.x() : 0.0;
  const double inv_y = sy != 0 ? 1.0 / d.y() : 0.0;
  const auto near_x = [&](int i) {
    return sx > 0 ? (i + 1 - o.x()) * inv_x : (sx < 0 ? (i - o.x()) * inv_x : kInf);
  };
  const auto near_y = [&](int i) {
    return sy > 0 ? (i + 1 - o.y()) * inv_y : (sy < 0 ? (i - o.y()) * inv_y : kInf);
  };
  // Whether two approximate times are too close to order (infinite ones are exact).
  const auto close = [&](double a, double b) {
    return a != kInf && b != kInf && std::abs(a - b) <= kRel * std::max(std::abs(a), std::abs(b));
  };
  const int ix0 = ix, iy0 = iy;
  // The exact entry time of cell (x, y) of the walk.
  const auto entry = [&](int x, int y) {
    double t = t0;
    if (x != ix0) t = std::max(t, exit_x(x - sx));
    if (y != iy0) t = std::max(t, exit_y(y - sy));
    return t;
  };
  // !(tn <= t_max) for the exact tn that `approx` stands for, where `exact` computes it.
  const auto beyond = [&](double approx, auto&& exact) {
    if (t_max == kInf || approx <= t_max * (1.0 - kRel)) return false;
    if (approx > t_max * (1.0 + kRel)) return true;
    return !(exact() <= t_max);
  };
  double t = t0;  // approximate entry time of (ix, iy)
  double tx = near_x(ix), ty = near_y(iy);
  for (;;) {
    const std::size_t cell = static_cast<std::size_t>(iy) * width_ + ix;
    if (occupied_[cell] != 0) return std::min(entry(ix, iy) * resolution_, max_range);
    if (const int run = free_run_[cell]; run >= kMinJump) {
      const double target = t + run * (1.0 / kFreeRunUnits);
      double entered = t;
      // On one axis (`exit` and `near` its exact and approximate boundary times, `coord` the
      // origin's coordinate, `d` the direction's): the line the walk is in after all events
      // before `target`, from line i whose approximate exit time is `t_next` (updated).
      const auto land = [&](auto&& exit, auto&& near, double coord, double d, int step, int i,
                            double& t_next) {
        // exit(i) < target, exactly; `approx` is near(i).
        const auto before = [&](int line, double approx) {
          if (std::abs(approx - target) > kRel * target) return approx < target;
          return exit(line) < target;
        };
        if (step == 0 || !before(i, t_next)) return i;
        const double guess = std::floor(coord + target * d);
        int g = guess * step > (i + step) * step ? static_cast<int>(guess) : i + step;
        double at = near(g);
        while (before(g, at)) at = near(g += step);
        for (double prev; g - step != i && !before(g - step, prev = near(g - step)); at = prev)
          g -= step;
        t_next = at;
        entered = std::max(entered, near(g - step));
        return g;
      };
      const int jx = land(exit_x, near_x, o.x(), d.x(), sx, ix, tx);
      const int jy = land(exit_y, near_y, o.y(), d.y(), sy, iy, ty);
      if (jx != ix || jy != iy) {
        // The walk would have stopped on the way: past max_range, or out of the grid.
        if (beyond(entered, [&] { return entry(jx, jy); })) return max_range;
        if (jx < 0 || jy < 0 || jx >= width_ || jy >= height_) return max_range;
        ix = jx;
        iy = jy;
        t = entered;
        continue;
      }
    }
    bool step_x = tx < ty, step_y = ty < tx;
    if (close(tx, ty)) {
      const double ex = exit_x(ix), ey = exit_y(iy);
      step_x = ex < ey;
      step_y = ey < ex;
    }
    const double tn = std::max(t, std::min(tx, ty));
    const auto exact_tn = [&] { return std::max(entry(ix, iy), std::min(exit_x(ix), exit_y(iy))); };
    if (beyond(tn, exact_tn)) return max_range;
    if (step_x) {
      ix += sx;
      tx = near_x(ix);
    } else if (step_y) {
      iy += sy;
      ty = near_y(iy);
    } else {
      // Through a corner: the two cells that share it are touched too (closed squares).
      if (occupied(ix + sx, iy) || occupied(ix, iy + sy)) {
        return std::min(exact_tn() * resolution_, max_range);
      }
      ix += sx;
      iy += sy;
      tx = near_x(ix);
      ty = near_y(iy);
    }
    t = tn;
    if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return max_range;
  }
}

}  // namespace floornav
