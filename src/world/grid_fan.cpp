#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <optional>
#include <type_traits>
#include <utility>

#include "cell_index.hpp"
#include "floornav/core/isa_clones.hpp"
#include "floornav/geometry/fan_cone.hpp"
#include "floornav/geometry/fan_layout.hpp"
#include "floornav/geometry/ray.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "grid_walk.hpp"

// OccupancyGrid::cast_fan: a lidar's beams from one origin, tested against the runs of occupied
// cells that a walk can enter first (gathered once, when the grid is built).

namespace floornav {

using cell_detail::clamp_cell;
using grid_detail::kInf;

// The side of the square tiles (cells) the runs are kept by: smaller tiles cut more runs at
// their borders and cost more to pass over, larger ones cull less. BM_CaveGridCastFanHalfTurn180
// and BM_GridCastFan360 (bench/grid_bench.cpp) and the peer harness's cave (bench/peers) decide it.
constexpr int kTile = OccupancyGrid::kFanTile;

namespace {

// Labels the free cells by their 4-connected components: label[c] for free cell c, -1 for an
// occupied one. Outside the grid counts as free and is component 0 with every free cell it
// touches (possibly none); the others are numbered from 1, the largest first.
std::vector<std::int32_t> free_components(const std::vector<std::uint8_t>& occupied, int width,
                                          int height) {
  const std::size_t w = static_cast<std::size_t>(width);
  std::vector<std::int32_t> label(occupied.size(), -1);
  std::vector<std::size_t> stack;
  const auto flood = [&](std::size_t seed, std::int32_t id) {
    if (occupied[seed] != 0 || label[seed] >= 0) return;
    label[seed] = id;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::size_t c = stack.back();
      stack.pop_back();
      const std::size_t x = c % w, y = c / w;
      const auto visit = [&](std::size_t n) {
        if (occupied[n] == 0 && label[n] < 0) {
          label[n] = id;
          stack.push_back(n);
        }
      };
      if (x > 0) visit(c - 1);
      if (x + 1 < w) visit(c + 1);
      if (y > 0) visit(c - w);
      if (y + 1 < static_cast<std::size_t>(height)) visit(c + w);
    }
  };
  for (int x = 0; x < width; ++x) {
    flood(static_cast<std::size_t>(x), 0);
    flood(static_cast<std::size_t>(height - 1) * w + x, 0);
  }
  for (int y = 0; y < height; ++y) {
    flood(static_cast<std::size_t>(y) * w, 0);
    flood(static_cast<std::size_t>(y) * w + w - 1, 0);
  }
  std::int32_t next = 1;
  for (std::size_t c = 0; c < label.size(); ++c)
    if (occupied[c] == 0 && label[c] < 0) flood(c, next++);
  // Renumbered by size, largest first (after 0): a tile's runs are kept in component order, and
  // a fan from the main floor then stops at the runs of the pockets behind them.
  std::vector<std::int64_t> size(static_cast<std::size_t>(next), 0);
  for (const std::int32_t l : label)
    if (l >= 0) ++size[static_cast<std::size_t>(l)];
  std::vector<std::int32_t> order(static_cast<std::size_t>(next));
  for (std::int32_t i = 0; i < next; ++i) order[static_cast<std::size_t>(i)] = i;
  std::stable_sort(order.begin() + 1, order.end(), [&](std::int32_t a, std::int32_t b) {
    return size[static_cast<std::size_t>(a)] > size[static_cast<std::size_t>(b)];
  });
  std::vector<std::int32_t> renamed(static_cast<std::size_t>(next));
  for (std::int32_t i = 0; i < next; ++i)
    renamed[static_cast<std::size_t>(order[static_cast<std::size_t>(i)])] = i;
  for (std::int32_t& l : label)
    if (l >= 0) l = renamed[static_cast<std::size_t>(l)];
  return label;
}

}  // namespace

void OccupancyGrid::compute_boundary() {
  free_component_ = free_components(occupied_, width_, height_);
  // The component of a cell, outside the grid included; -1 for an occupied cell.
  const auto component = [&](int x, int y) -> std::int32_t {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return 0;
    return free_component_[static_cast<std::size_t>(y) * width_ + x];
  };
  const auto occupied_at = [&](int x, int y) {
    return occupied_[static_cast<std::size_t>(y) * width_ + x] != 0;
  };
  constexpr int T = kTile;
  tile_cols_ = (width_ + T - 1) / T;
  tile_rows_ = (height_ + T - 1) / T;
  const std::size_t tiles = static_cast<std::size_t>(tile_cols_) * tile_rows_;
  // A run is taken by the fans from origins in the component of free cells its cells face (the
  // side's neighbours: one component per run). The least distance of a fan's beam is that of
  // such a run. The walk is in a free cell W of the origin's component until that distance; then
  // it steps into a neighbour of W (whose neighbour facing the walk is W) or passes a corner,
  // touching the two cells beside it: an occupied one faces W, and when both are free (then in
  // W's component) the diagonal cell faces one of them. Either cell is on a side the walk comes
  // from. So the far side of a hollow outline (facing its inside) is left out from outside.
  std::vector<Run> runs[4];
  const auto tile_of = [&](int s, const Run& r) {
    const bool rows = s >= 2;
    const int x = rows ? r.first : r.line, y = rows ? r.line : r.first;
    return static_cast<std::size_t>(y / T) * tile_cols_ + static_cast<std::size_t>(x / T);
  };
  for (int s = 0; s < 4; ++s) {
    const bool rows = s >= 2;  // runs along rows (of columns)
    const int lines = rows ? height_ : width_;
    const int along = rows ? width_ : height_;
    const int dx = s == 0 ? -1 : (s == 1 ? 1 : 0);
    const int dy = s == 2 ? -1 : (s == 3 ? 1 : 0);
    for (int l = 0; l < lines; ++l) {
      int open = -1;
      std::int32_t open_component = -1;
      for (int i = 0; i <= along; ++i) {
        const int x = rows ? i : l, y = rows ? l : i;
        // The component this cell's run faces, -1 for a cell in no run.
        const std::int32_t c = i < along && occupied_at(x, y) ? component(x + dx, y + dy) : -1;
        if (open >= 0 && c != open_component) {
          runs[s].push_back({l, open, i - 1, open_component, 0});
          open = -1;
        }
        if (c >= 0 && open < 0) open = i, open_component = c;
        // A run ends at a tile border too.
        if (open >= 0 && i % T == T - 1) {
          runs[s].push_back({l, open, i, open_component, 0});
          open = -1;
        }
      }
    }
  }
  // Runs of one cell that another run tests for them (the cave's walls are mostly staircases,
  // whose cells have two such faces). Run r1 of cell c and side s1 (say the left face, 0) is
  // covered by run R of a perpendicular side s2 (say the bottom faces of a row, 2) in the same
  // component that ends at c on r1's side (c is R's first cell). A walk from an origin both
  // face (left of c's column, below its row) that enters c through its left face moves right
  // and up, so it crossed R's face line left of c, beyond R's end: R's test of that walk falls
  // back to the exact test of the cells near the crossing clamped to R, c among them. R's box
  // holds c, so R's beams and distance cover c's. A fan from such an origin leaves r1 out. R is
  // longer than one cell or of a later side, so the relation has no cycle: R is tested.
  for (int s1 = 0; s1 < 4; ++s1) {
    const bool rows1 = s1 >= 2;
    for (Run& r1 : runs[s1]) {
      if (r1.first != r1.last) continue;
      // The cell's row (for a face of a column run) or column, and its place along it.
      const int line = r1.first, at = r1.line;
      for (const int s2 : rows1 ? std::array{0, 1} : std::array{2, 3}) {
        // runs[s2] is in order of line, then of first cell: the run of `line` holding `at`.
        const auto after =
            std::upper_bound(runs[s2].begin(), runs[s2].end(), std::pair{line, at},
                             [](const std::pair<int, int>& p, const Run& r) {
                               return p.first < r.line || (p.first == r.line && p.second < r.first);
                             });
        if (after == runs[s2].begin()) continue;
        const Run& r2 = *std::prev(after);
        const bool at_end = s1 % 2 == 0 ? r2.first == at : r2.last == at;  // left, bottom: first
        if (r2.line == line && at_end && r2.component == r1.component &&
            (r2.first != r2.last || s2 > s1))
          r1.cover |= 1 << s2;
      }
    }
  }
  tile_start_.assign(4 * tiles + 1, 0);
  for (int s = 0; s < 4; ++s)
    for (const Run& r : runs[s]) ++tile_start_[4 * tile_of(s, r) + s + 1];
  for (std::size_t i = 1; i < tile_start_.size(); ++i) tile_start_[i] += tile_start_[i - 1];
  tile_runs_.resize(static_cast<std::size_t>(tile_start_.back()));
  std::vector<std::int32_t> fill(tile_start_.begin(), tile_start_.end() - 1);
  tile_box_.assign(tiles, CellBox{width_, 0, height_, 0});
  for (int s = 0; s < 4; ++s) {
    const bool rows = s >= 2;
    for (const Run& r : runs[s]) {
      const std::size_t t = tile_of(s, r);
      tile_runs_[fill[4 * t + s]++] = r;
      CellBox& b = tile_box_[t];
      const int x0 = rows ? r.first : r.line, x1 = rows ? r.last + 1 : r.line + 1;
      const int y0 = rows ? r.line : r.first, y1 = rows ? r.line + 1 : r.last + 1;
      b = {std::min(b.x0, x0), std::max(b.x1, x1), std::min(b.y0, y0), std::max(b.y1, y1)};
    }
  }
  // Each tile's side by component (then line and place, as built): a fan takes one component.
  for (std::size_t g = 0; g + 1 < tile_start_.size(); ++g)
    std::stable_sort(tile_runs_.begin() + tile_start_[g], tile_runs_.begin() + tile_start_[g + 1],
                     [](const Run& a, const Run& b) { return a.component < b.component; });
}

// The fan's work is the bulk of a lidar robot's step, so it gets an x86-64-v3 clone with the
// same results; BM_CaveGridCastFan180 (bench/grid_bench.cpp) decides whether the clone pays.
FLOORNAV_ISA_CLONES
void OccupancyGrid::cast_fan(const Vec2& origin_world, std::span<const Vec2> dirs,
                             std::span<const double> angles, double max_range,
                             std::span<double> out, FanScratch& scratch) const {
  const std::size_t n = dirs.size();
  const auto ray_by_ray = [&] {
    for (std::size_t i = 0; i < n; ++i) out[i] = cast_ray(origin_world, dirs[i], max_range);
  };
  // What `cast` computes first, to the bit.
  const Vec2 o = to_grid(origin_world) / resolution_;
  if (n < 2 || !is_finite(o) || !(max_range >= 0.0) || !std::isfinite(max_range)) {
    return ray_by_ray();
  }
  const double t_max = max_range / resolution_;
  // The fan handles an origin in a free cell of the grid (then `cast` starts its walk at t0 = 0
  // in cell (ix0, iy0)), and one outside the grid, more than kOutside cells from it, that the
  // grid is within reach of. From outside, `cast` clips each ray to the grid and starts its walk
  // where the ray enters, at t0 in the cell there; everything below takes the walk as if it
  // started at t = 0 in the origin's cell (ix0, iy0) of the grid extended by free cells. Both
  // give a cell of the grid the same entry time where the ray enters the grid through the
  // inside of a border cell's face: that face's quotient is the clipping's t0 (the same division
  // by the same numbers), the entry cell's other line was entered before t0, and the walks take
  // the same events after it. Rays that enter within kCorner of a cell corner go ray by ray.
  constexpr double kOutside = 1e-5;        // cells
  constexpr double kMaxOutside = 1 << 24;  // cells: the cell indices below stay exact ints
  const bool inside = o.x() >= 0.0 && o.x() < width_ && o.y() >= 0.0 && o.y() < height_;
  int ix0 = 0, iy0 = 0;
  if (inside) {
    ix0 = clamp_cell(o.x(), width_);
    iy0 = clamp_cell(o.y(), height_);
    if (occupied_[static_cast<std::size_t>(iy0) * width_ + ix0] != 0) return ray_by_ray();
  } else {
    const double gx = std::max(-o.x(), o.x() - width_), gy = std::max(-o.y(), o.y() - height_);
    if (!(std::max(gx, gy) > kOutside) || !(std::abs(o.x()) < kMaxOutside) ||
        !(std::abs(o.y()) < kMaxOutside))
      return ray_by_ray();
    ix0 = static_cast<int>(std::floor(o.x()));
    iy0 = static_cast<int>(std::floor(o.y()));
  }
  // Only runs that walks from the origin's component of free cells can touch first.
  const std::int32_t component =
      inside ? free_component_[static_cast<std::size_t>(iy0) * width_ + ix0] : 0;
  const std::optional<fan_detail::FanLayout> fan = fan_detail::even_fan(angles);
  if (!fan) return ray_by_ray();

  if (scratch.dx.size() < n) {
    scratch.dx.resize(n);
    scratch.dy.resize(n);
    scratch.best.resize(n);
  }
  double* dx = scratch.dx.data();
  double* dy = scratch.dy.data();
  double* best = scratch.best.data();
  {
    // Locals, so that the stores below need not reload them (and the loop vectorises).
    const double c = cos_yaw_, s = sin_yaw_;
    for (std::size_t i = 0; i < n; ++i) {
      const double x = dirs[i].x(), y = dirs[i].y();
      const double gx = c * x + s * y, gy = -s * x + c * y;
      dx[i] = gx;
      dy[i] = gy;
      // The culling below assumes a unit direction at the given angle; other beams are cast ray
      // by ray, marked by best = -inf (no test takes them: every lower bound is above).
      const double len2 = gx * gx + gy * gy;
      best[i] = std::abs(len2 - 1.0) <= 1e-6 ? kInf : -kInf;
    }
  }
  if (!inside) {
    // Where each ray enters the grid (`cast`'s clipping): near a cell corner, ray by ray.
    constexpr double kCorner = 1e-9;  // cells, relative
    const Box2 cells{Vec2(0.0, 0.0), Vec2(width_, height_)};
    const auto near_line = [&](double v) {
      return std::abs(v - fan_detail::floor_by_truncation(v + 0.5)) <=
             kCorner * (1.0 + std::abs(v));
    };
    for (std::size_t i = 0; i < n; ++i) {
      double t0 = 0.0, t1 = t_max;
      if (best[i] == -kInf || !clip_ray_to_box(o, Vec2(dx[i], dy[i]), cells, t0, t1)) continue;
      const double px = o.x() + t0 * dx[i], py = o.y() + t0 * dy[i];
      if (!(px > -0.5 && py > -0.5) || (near_line(px) && near_line(py))) best[i] = -kInf;
    }
  }

  // The walk from (ix0, iy0) enters or touches (through a corner) cell (x, y) exactly when the
  // latest of the events that bring it into the cell's column and row (the boundary quotients
  // exit_x(x - sx), exit_y(y - sy); t0 = 0 for the origin's own column or row) is not after the
  // earliest of those that take it out (exit_x(x), exit_y(y)): it takes the events in increasing
  // order, a tie being a corner step that touches both side cells. That latest event is the
  // distance it returns for the cell (its running maximum), and it returns the first occupied
  // cell within t_max, whose distance is the least. So the minimum over the occupied cells below
  // is `cast`'s answer to the bit; cells no walk can reach first only need to be left out.
  // On one axis: the times the walk enters (a) and leaves (b) line c of the cells, from origin
  // coordinate oc in line c0 along direction component d; false when it never gets there.
  const auto axis_times = [](double d, int c, int c0, double oc, double& a, double& b) {
    if (d > 0.0) {
      if (c < c0) return false;
      if (c != c0) a = (c - oc) / d;
      b = (c + 1 - oc) / d;
    } else if (d < 0.0) {
      if (c > c0) return false;
      if (c != c0) a = (c + 1 - oc) / d;
      b = (c - oc) / d;
    } else if (c != c0) {
      return false;
    }
    return true;
  };
  const auto test = [axis_times, best, dx, dy, ix0, iy0, ox = o.x(), oy = o.y(), t_max](
                        int k, int x, int y) {
    if (best[k] == -kInf) return;
    double ax = 0.0, bx = kInf, ay = 0.0, by = kInf;
    if (!axis_times(dx[k], x, ix0, ox, ax, bx) || !axis_times(dy[k], y, iy0, oy, ay, by)) return;
    const double h = std::max(0.0, std::max(ax, ay));
    if (h <= std::min(bx, by) && h <= t_max && h < best[k]) best[k] = h;
  };

  // Cells whose nearest point is farther than t_max (with room for |dir| and rounding) cannot
  // be reached within t_max.
  const double reach = t_max * (1.0 + 1e-5) + 1e-6;
  const double reach2 = reach * reach;
  const double yaw = origin_.theta;
  const fan_detail::FanCone cone(*fan, yaw);
  // Calls f(k) for the beams within the angular extent of box [x0, x1] x [y0, y1] (cells), at
  // gap2 (> 1e-12) from the origin, and possibly a few more: those whose angle lies between the
  // box's silhouette corners as seen from the origin (outside the box), the clockwise-most one
  // then counter-clockwise (less than pi) to the other, widened by kFanMargin on each side.
  const auto for_beams_towards = [&](double x0, double x1, double y0, double y1, auto&& f) {
    const double ox = o.x(), oy = o.y();
    const double cw_x = oy < y0 ? x1 : (oy > y1 ? x0 : (ox > x1 ? x1 : x0));
    const double cw_y = ox > x1 ? y1 : (ox < x0 ? y0 : (oy < y0 ? y0 : y1));
    const double ccw_x = oy > y1 ? x1 : (oy < y0 ? x0 : (ox < x0 ? x0 : x1));
    const double ccw_y = ox < x0 ? y1 : (ox > x1 ? y0 : (oy > y1 ? y1 : y0));
    return cone.for_beams(cw_x - ox, cw_y - oy, ccw_x - ox, ccw_y - oy, f);
  };
  // How far inside a face its crossing b must be for the face's own quotient to be the run's
  // distance: far more than b's rounding, 1e-16 (|q| + |o|), for every q <= reach. A crossing
  // farther than t_max (> q) gives no hit either way: every cell of the run is entered after it.
  const double face_eps = 1e-10 * (1.0 + reach + std::max(std::abs(o.x()), std::abs(o.y())));
  // Run `r` of side `s` on line `l`: the box [x0, x1] x [y0, y1] of its cells.
  const auto run = [&](auto side, int l, const Run& r) {
    constexpr int s = decltype(side)::value;
    constexpr bool rows = s >= 2;
    const double x0 = rows ? r.first : l, x1 = rows ? r.last + 1.0 : l + 1.0;
    const double y0 = rows ? l : r.first, y1 = rows ? l + 1.0 : r.last + 1.0;
    const double ox = o.x(), oy = o.y();
    // The origin is beyond the run's side: left of x0 for side 0 (its column is left of the
    // run's), right of x1 (or on it) for side 1, below y0 for 2, above y1 (or on it) for 3.
    const double gx = s == 0 ? x0 - ox : (s == 1 ? ox - x1 : std::max({0.0, x0 - ox, ox - x1}));
    const double gy = s == 2 ? y0 - oy : (s == 3 ? oy - y1 : std::max({0.0, y0 - oy, oy - y1}));
    const double gap2 = gx * gx + gy * gy;
    if (gap2 > reach2) return;
    // A walk enters the box no earlier than its distance (|dir| <= 1 + 1e-6); a beam that
    // already has a nearer hit needs no test (the minimum is the same).
    const double lower = std::sqrt(gap2) * (1.0 - 1e-5);
    // The face of the run that facing walks cross: the line a = face of axis a (0: x = face,
    // 1: y = face). A walk crosses it with the event q = (face - o_a) / d_a, the very quotient it
    // computes, at b = o_b + q d_b on the other axis (to within far less than face_eps). When b is
    // inside the face, away from its ends, the walk enters the run's line there, in a cell of
    // the run (or touches one through a corner at that event), and it has touched none of the
    // line before: the run's first distance is max(0, q) exactly (max(t0, ...) as the walk
    // keeps it). Otherwise (near an end, or entering the box through an end) the cells of the
    // run within a cell of floor(b), clamped to the run, are tested with the walk's exact test.
    constexpr int axis = rows ? 1 : 0;
    const double face = (s == 0 || s == 2) ? l : l + 1.0;
    const double oa = o[axis], ob = o[1 - axis];
    const double lo = r.first, hi = r.last;
    const auto cell_test = [&](int k, int c) {
      if constexpr (rows) {
        test(k, c, l);
      } else {
        test(k, l, c);
      }
    };
    // The run's numbers by value (one load each in the loop over the beams, not two).
    const auto each = [&, best, lower, face_oa = face - oa, ob, inside_lo = lo + face_eps,
                       inside_hi = hi + 1.0 - face_eps, t_max, da_of = axis == 0 ? dx : dy,
                       db_of = axis == 0 ? dy : dx](int k) {
      if (lower > best[k]) return;
      const double da = da_of[k], db = db_of[k];
      if constexpr (s == 0 || s == 2) {
        if (!(da > 0.0)) return;  // moving away from the face
      } else {
        if (!(da < 0.0)) return;
      }
      const double q = face_oa / da;
      const double b = ob + q * db;
      if (b >= inside_lo && b <= inside_hi) {
        const double h = std::max(0.0, q);
        if (h <= t_max && h < best[k]) best[k] = h;
        return;
      }
      if (!(b == b)) {
        for (int c = r.first; c <= r.last; ++c) cell_test(k, c);
        return;
      }
      const double fb = fan_detail::floor_by_truncation(b);
      const int c0 = static_cast<int>(std::clamp(fb - 1.0, lo, hi));
      const int c1 = static_cast<int>(std::clamp(fb + 1.0, lo, hi));
      for (int c = c0; c <= c1; ++c) cell_test(k, c);
    };
    if (gap2 < 1e-12) {
      for (int k = 0; k < fan->n; ++k) each(k);
      return;
    }
    // The box's silhouette corners (as in for_beams_towards) for an origin on the run's side.
    double cw_x, cw_y, ccw_x, ccw_y;
    if constexpr (s == 0) {
      cw_x = oy < y0 ? x1 : x0, cw_y = y0, ccw_x = oy > y1 ? x1 : x0, ccw_y = y1;
    } else if constexpr (s == 1) {
      cw_x = oy > y1 ? x0 : x1, cw_y = y1, ccw_x = oy < y0 ? x0 : x1, ccw_y = y0;
    } else if constexpr (s == 2) {
      cw_x = x1, cw_y = ox > x1 ? y1 : y0, ccw_x = x0, ccw_y = ox < x0 ? y1 : y0;
    } else {
      cw_x = x0, cw_y = ox < x0 ? y0 : y1, ccw_x = x1, ccw_y = ox > x1 ? y0 : y1;
    }
    cone.for_beams(cw_x - ox, cw_y - oy, ccw_x - ox, ccw_y - oy, each);
  };
  // Tile (tx, ty)'s runs of side s of the origin's component (together, in component order)
  // that face the origin: side 0 on columns right of the origin's column, 1 on those left of it,
  // 2 on rows above, 3 on rows below. None does when all the tile's lines lie on the wrong side.
  const auto tile_side = [&](auto side, std::size_t t, int tx, int ty) {
    constexpr int s = decltype(side)::value;
    if ((s == 0 && tx * kTile + kTile - 1 <= ix0) || (s == 1 && tx * kTile >= ix0) ||
        (s == 2 && ty * kTile + kTile - 1 <= iy0) || (s == 3 && ty * kTile >= iy0))
      return;
    const Run* r = tile_runs_.data() + tile_start_[4 * t + s];
    const Run* end = tile_runs_.data() + tile_start_[4 * t + s + 1];
    while (r != end && r->component < component) ++r;
    for (; r != end && r->component == component; ++r) {
      const bool faces = s == 0   ? r->line > ix0
                         : s == 1 ? r->line < ix0
                         : s == 2 ? r->line > iy0
                                  : r->line < iy0;
      if (!faces) continue;
      if (r->cover != 0) {
        // Left out when a run that tests its cell for it faces the origin too.
        const int cx = s >= 2 ? r->first : r->line, cy = s >= 2 ? r->line : r->first;
        if (((r->cover & 1) && cx > ix0) || ((r->cover & 2) && cx < ix0) ||
            ((r->cover & 4) && cy > iy0) || ((r->cover & 8) && cy < iy0))
          continue;
      }
      run(side, r->line, *r);
    }
  };
  // Whether some beam may still take a hit from a cell of box [x0, x1] x [y0, y1] (the box of a
  // tile's runs): a beam within the box's angular extent whose hit so far (or t_max) is not
  // nearer than the box's lower bound. When none may, `run` would leave every run of the box
  // untested: each of its beams is either outside the run's extent (the run's box is inside), so
  // its walk touches no cell of the run, or sees the run's lower bound (not below the box's) above
  // its hit so far or above t_max, which a hit h >= lower bound cannot beat.
  //
  // First, without an atan2: a fan narrower than a full turn (a lidar of 180 degrees) leaves out
  // the boxes that lie wholly behind it. Every beam is within half_width (+ 1e-8 for the angles'
  // tolerance and the rounding of the directions) of the fan's centre line c. The points p (from
  // the origin) more than `behind` >= pi / 2 from c form a convex cone, so a box whose four
  // corners are in it lies in it, and no beam passes through it.
  const double half_width = 0.5 * (fan->n - 1) * fan->step;
  const double behind = std::max(half_width + fan_detail::kFanMargin, 0.5 * kPi);
  const bool cone_test = behind < kPi;
  const double centre = fan->first + half_width - yaw;
  const double cx = std::cos(centre), cy = std::sin(centre);
  const double cos_behind = std::cos(behind);  // <= 0
  const auto wholly_behind = [&](double x0, double x1, double y0, double y1) {
    const auto corner_behind = [&](double x, double y) {
      const double px = x - o.x(), py = y - o.y();
      const double along = px * cx + py * cy;
      return along < 0.0 && along * along > cos_behind * cos_behind * (px * px + py * py);
    };
    return cone_test && corner_behind(x0, y0) && corner_behind(x1, y0) && corner_behind(x0, y1) &&
           corner_behind(x1, y1);
  };
  const auto wanted = [&](double x0, double x1, double y0, double y1) {
    const double gx = std::max({0.0, x0 - o.x(), o.x() - x1});
    const double gy = std::max({0.0, y0 - o.y(), o.y() - y1});
    const double gap2 = gx * gx + gy * gy;
    if (gap2 > reach2) return false;
    if (gap2 < 1e-12) return true;
    if (wholly_behind(x0, x1, y0, y1)) return false;
    const double lower = std::sqrt(gap2) * (1.0 - 1e-5);
    // lower <= min(best[k], t_max) for a beam not cast ray by ray (best[k] != -inf): as lower
    // >= 0, the same as lower <= t_max (once) and lower <= best[k].
    if (!(lower <= t_max)) return false;
    return for_beams_towards(x0, x1, y0, y1, [&](int k) { return lower <= best[k]; });
  };
  // The tiles in rings about the origin's tile (ring r: Chebyshev distance r in tiles), nearest
  // first, so that near hits skip the tiles behind them. Every cell of ring r >= 1 is at least
  // (r - 1) * kTile cells from the origin: past the farthest a beam can still reach, stop.
  constexpr int T = kTile;
  // Floor division: an origin outside the grid may have negative cells.
  const auto tile_of = [](int c) { return c >= 0 ? c / T : -((-c + T - 1) / T); };
  const int tx0 = tile_of(ix0), ty0 = tile_of(iy0);
  const auto tile = [&](int tx, int ty) {
    const std::size_t t = static_cast<std::size_t>(ty) * tile_cols_ + tx;
    if (tile_start_[4 * t] == tile_start_[4 * t + 4]) return;
    // The box of the tile's runs: every cell a run of it holds is in there.
    const CellBox& b = tile_box_[t];
    if (!wanted(b.x0, b.x1, b.y0, b.y1)) return;
    tile_side(std::integral_constant<int, 0>{}, t, tx, ty);
    tile_side(std::integral_constant<int, 1>{}, t, tx, ty);
    tile_side(std::integral_constant<int, 2>{}, t, tx, ty);
    tile_side(std::integral_constant<int, 3>{}, t, tx, ty);
  };
  // The farthest any beam can still take a hit (cell units): t_max at first, lowered every
  // fourth ring (the loop costs a few rings' work) and tested at every ring (it only falls).
  double farthest = t_max;
  for (int ring = 0;; ++ring) {
    if (ring >= 2 && ring % 4 == 0) {
      // A beam cast ray by ray (best = -inf) raises nothing.
      // Four lanes at a time (GCC's vector extensions); the maximum is the same in any order.
      using V4d = double __attribute__((vector_size(32)));
      V4d f = V4d{} - kInf;
      std::size_t k = 0;
      for (; k + 4 <= n; k += 4) {
        V4d b;
        std::memcpy(&b, best + k, sizeof b);
        const V4d cap = b < t_max ? b : t_max;
        f = f < cap ? cap : f;
      }
      double f0 = std::max(std::max(f[0], f[1]), std::max(f[2], f[3]));
      for (; k < n; ++k) f0 = std::max(f0, best[k] < t_max ? best[k] : t_max);
      farthest = f0;
    }
    if (ring >= 2 && (ring - 1.0) * T * (1.0 - 1e-5) > farthest) break;
    const int xa = tx0 - ring, xb = tx0 + ring, ya = ty0 - ring, yb = ty0 + ring;
    if (xa < 0 && ya < 0 && xb >= tile_cols_ && yb >= tile_rows_) break;
    // The ring's four sides, each a row or column of tiles clipped to the grid (a ring about an
    // origin outside the grid may have a side beyond it), passed over at once when the whole
    // side lies beyond reach or behind the fan (a box whose corners are behind is behind).
    // (One call site, so that the ring's work is one piece of code.)
    for (int e = 0; e < 4; ++e) {
      if ((e == 1 && yb == ya) || (e == 3 && xb == xa)) continue;
      // e: the bottom row, the top row, the left column, the right column (without corners).
      int x0 = e == 3 ? xb : xa, x1 = e == 2 ? xa : xb;
      int y0 = e == 0 ? ya : (e == 1 ? yb : ya + 1), y1 = e == 0 ? ya : (e == 1 ? yb : yb - 1);
      x0 = std::max(x0, 0), x1 = std::min(x1, tile_cols_ - 1);
      y0 = std::max(y0, 0), y1 = std::min(y1, tile_rows_ - 1);
      if (x0 > x1 || y0 > y1) continue;
      const double bx0 = x0 * T, bx1 = std::min(x1 * T + T, width_);
      const double by0 = y0 * T, by1 = std::min(y1 * T + T, height_);
      const double gx = std::max({0.0, bx0 - o.x(), o.x() - bx1});
      const double gy = std::max({0.0, by0 - o.y(), o.y() - by1});
      if (gx * gx + gy * gy > reach2 || wholly_behind(bx0, bx1, by0, by1)) continue;
      for (int ty = y0; ty <= y1; ++ty)
        for (int tx = x0; tx <= x1; ++tx) tile(tx, ty);
    }
  }
  // Cell units to metres (+inf, no hit, to max_range, which is finite); then the beams marked
  // -inf, the only negative results (but for a max_range of -0), cast ray by ray: in a second
  // pass, so that the first vectorises.
  const double res = resolution_;
  double* result = out.data();
  std::uint64_t signs = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = std::min(best[i] * res, max_range);
    result[i] = r;
    signs |= std::bit_cast<std::uint64_t>(r);
  }
  if ((signs >> 63) != 0) {
    for (std::size_t i = 0; i < n; ++i)
      if (best[i] == -kInf) result[i] = cast_ray(origin_world, dirs[i], max_range);
  }
}

void OccupancyGrid::cast_fan(const Vec2& origin_world, std::span<const Vec2> dirs,
                             std::span<const double> angles, double max_range,
                             std::span<double> out) const {
  FanScratch scratch;
  cast_fan(origin_world, dirs, angles, max_range, out, scratch);
}

}  // namespace floornav
