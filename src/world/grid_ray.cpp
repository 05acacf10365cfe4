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

namespace {

// The arithmetic of OccupancyGrid::walk_with_jumps on one ray (cell units, grid frame): the
// exact boundary times (the quotients `cast` computes), their approximations by products with
// 1 / d, and the decisions between them. The ray starts in cell (ix0, iy0) at t0.
class JumpWalk {
 public:
  // Decisions closer than this (relative) are made with the exact quotients: the products
  // differ from them by a few ulps (kRel covers them a thousandfold).
  static constexpr double kRel = 1e-13;

  JumpWalk(const Vec2& o, const Vec2& d, double t_max, double t0, int ix0, int iy0)
      : o_(o),
        d_(d),
        sx_(d.x() > 0.0 ? 1 : (d.x() < 0.0 ? -1 : 0)),
        sy_(d.y() > 0.0 ? 1 : (d.y() < 0.0 ? -1 : 0)),
        column_{o.x(), d.x(), sx_},
        row_{o.y(), d.y(), sy_},
        inv_x_(sx_ != 0 ? 1.0 / d.x() : 0.0),
        inv_y_(sy_ != 0 ? 1.0 / d.y() : 0.0),
        t_max_(t_max),
        t0_(t0),
        ix0_(ix0),
        iy0_(iy0) {}

  int sx() const { return sx_; }
  int sy() const { return sy_; }

  // The exact time the walk leaves line i of axis A (0: columns, 1: rows).
  template <int A>
  [[gnu::always_inline]] double exit(int i) const {
    if constexpr (A == 0) {
      return column_.exit(i);
    } else {
      return row_.exit(i);
    }
  }

  // exit<A>(i) approximated by a product with 1 / d.
  template <int A>
  [[gnu::always_inline]] double near(int i) const {
    const int step = A == 0 ? sx_ : sy_;
    const double inv = A == 0 ? inv_x_ : inv_y_;
    return step > 0 ? (i + 1 - o_[A]) * inv : (step < 0 ? (i - o_[A]) * inv : kInf);
  }

  // Whether two approximate times are too close to order (infinite ones are exact).
  [[gnu::always_inline]] static bool close(double a, double b) {
    return a != kInf && b != kInf && std::abs(a - b) <= kRel * std::max(std::abs(a), std::abs(b));
  }

  // The exact entry time of cell (x, y) of the walk: the latest event before it.
  [[gnu::always_inline]] double entry(int x, int y) const {
    double t = t0_;
    if (x != ix0_) t = std::max(t, exit<0>(x - sx_));
    if (y != iy0_) t = std::max(t, exit<1>(y - sy_));
    return t;
  }

  // The exact time the walk leaves cell (x, y) (or touches the next through a corner).
  [[gnu::always_inline]] double exact_next(int x, int y) const {
    return std::max(entry(x, y), std::min(exit<0>(x), exit<1>(y)));
  }

  // !(tn <= t_max) for the exact time tn that `approx` stands for, where `exact()` computes it.
  template <class Exact>
  [[gnu::always_inline]] bool beyond(double approx, const Exact& exact) const {
    if (t_max_ == kInf || approx <= t_max_ * (1.0 - kRel)) return false;
    if (approx > t_max_ * (1.0 + kRel)) return true;
    return !(exact() <= t_max_);
  }

  // On axis A: the line the walk is in after all events before `target`, from line i whose
  // approximate exit time is `t_next` (updated); `entered` rises to the approximate time the walk
  // entered that line.
  template <int A>
  [[gnu::always_inline]] int land(double target, int i, double& t_next, double& entered) const {
    const int step = A == 0 ? sx_ : sy_;
    if (step == 0 || !before<A>(i, t_next, target)) return i;
    const double guess = std::floor(o_[A] + target * d_[A]);
    int g = guess * step > (i + step) * step ? static_cast<int>(guess) : i + step;
    double at = near<A>(g);
    while (before<A>(g, at, target)) at = near<A>(g += step);
    for (double prev; g - step != i && !before<A>(g - step, prev = near<A>(g - step), target);
         at = prev)
      g -= step;
    t_next = at;
    entered = std::max(entered, near<A>(g - step));
    return g;
  }

 private:
  // exit<A>(line) < target, exactly; `approx` is near<A>(line).
  template <int A>
  [[gnu::always_inline]] bool before(int line, double approx, double target) const {
    if (std::abs(approx - target) > kRel * target) return approx < target;
    return exit<A>(line) < target;
  }

  Vec2 o_, d_;
  int sx_, sy_;
  BoundaryTimes column_, row_;
  double inv_x_, inv_y_;
  double t_max_, t0_;
  int ix0_, iy0_;
};

}  // namespace

double OccupancyGrid::walk_with_jumps(const Vec2& o, const Vec2& d, double max_range, double t_max,
                                      double t0, int ix, int iy) const {
  // The walk of `cast`, to the same bits, with two changes.
  //
  // 1. It jumps over free space. A ray entering cell c runs free_run_[c] / 16 cells before it can
  //    touch an occupied square, so every cell it touches before t + run is free. The walk takes
  //    the boundary events (exit_x of successive columns, exit_y of successive rows; each list
  //    increasing) in increasing order, a tie being a corner step. So after all events before
  //    `target` it is in the first column jx with exit_x(jx) >= target, and likewise the row:
  //    that is where a jump lands (JumpWalk::land).
  // 2. It decides with products by 1 / d instead of quotients by d (JumpWalk::near); a decision
  //    too close to call is made with the quotients. The entry time of a cell is the latest
  //    event before it, that is the larger of exit_x of the previous column and exit_y of the
  //    previous row (or t0), so the exact time is only computed where it is returned or
  //    compared to t_max closely.
  const JumpWalk w(o, d, t_max, t0, ix, iy);
  const int sx = w.sx(), sy = w.sy();
  double t = t0;  // approximate entry time of (ix, iy)
  double tx = w.near<0>(ix), ty = w.near<1>(iy);
  for (;;) {
    const std::size_t cell = static_cast<std::size_t>(iy) * width_ + ix;
    if (occupied_[cell] != 0) return std::min(w.entry(ix, iy) * resolution_, max_range);
    if (const int run = free_run_[cell]; run >= kMinJump) {
      const double target = t + run * (1.0 / kFreeRunUnits);
      double entered = t;
      const int jx = w.land<0>(target, ix, tx, entered);
      const int jy = w.land<1>(target, iy, ty, entered);
      if (jx != ix || jy != iy) {
        // The walk would have stopped on the way: past max_range, or out of the grid.
        if (w.beyond(entered, [&] { return w.entry(jx, jy); })) return max_range;
        if (jx < 0 || jy < 0 || jx >= width_ || jy >= height_) return max_range;
        ix = jx;
        iy = jy;
        t = entered;
        continue;
      }
    }
    bool step_x = tx < ty, step_y = ty < tx;
    if (JumpWalk::close(tx, ty)) {
      const double ex = w.exit<0>(ix), ey = w.exit<1>(iy);
      step_x = ex < ey;
      step_y = ey < ex;
    }
    const double tn = std::max(t, std::min(tx, ty));
    if (w.beyond(tn, [&] { return w.exact_next(ix, iy); })) return max_range;
    if (step_x) {
      ix += sx;
      tx = w.near<0>(ix);
    } else if (step_y) {
      iy += sy;
      ty = w.near<1>(iy);
    } else {
      // Through a corner: the two cells that share it are touched too (closed squares).
      if (occupied(ix + sx, iy) || occupied(ix, iy + sy)) {
        return std::min(w.exact_next(ix, iy) * resolution_, max_range);
      }
      ix += sx;
      iy += sy;
      tx = w.near<0>(ix);
      ty = w.near<1>(iy);
    }
    t = tn;
    if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return max_range;
  }
}

}  // namespace floornav
