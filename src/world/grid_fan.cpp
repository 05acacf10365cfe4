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
#include "floornav/world/fan_index.hpp"
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
constexpr int kTile = OccupancyGrid::FanIndex::kTile;

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

// The stages of compute_boundary: each side's runs, the one-cell runs that another covers, and
// the runs bucketed by tile.
struct OccupancyGrid::BoundaryBuild {
  using Run = FanIndex::Run;
  using CellBox = FanIndex::CellBox;
  using Runs = std::array<std::vector<Run>, 4>;

  // The tile (row-major) that holds the first cell of run `r` of side `s`.
  static std::size_t tile_of(int s, const Run& r, int tile_cols) {
    const bool rows = s >= 2;
    const int x = rows ? r.first : r.line, y = rows ? r.line : r.first;
    return static_cast<std::size_t>(y / kTile) * tile_cols + static_cast<std::size_t>(x / kTile);
  }

  // The component of a cell, outside the grid included; -1 for an occupied cell.
  static std::int32_t component(const OccupancyGrid& g, const FanIndex& f, int x, int y) {
    if (x < 0 || y < 0 || x >= g.width_ || y >= g.height_) return 0;
    return f.free_component[static_cast<std::size_t>(y) * g.width_ + x];
  }

  // The runs of side `s` (see FanIndex::Run), line by line, each cut at tile borders.
  static void collect_side(const OccupancyGrid& g, const FanIndex& f, int s,
                           std::vector<Run>& runs) {
    const bool rows = s >= 2;  // runs along rows (of columns)
    const int lines = rows ? g.height_ : g.width_;
    const int along = rows ? g.width_ : g.height_;
    const int dx = s == 0 ? -1 : (s == 1 ? 1 : 0);
    const int dy = s == 2 ? -1 : (s == 3 ? 1 : 0);
    for (int l = 0; l < lines; ++l) {
      int open = -1;
      std::int32_t open_component = -1;
      for (int i = 0; i <= along; ++i) {
        const int x = rows ? i : l, y = rows ? l : i;
        const bool occupied =
            i < along && g.occupied_[static_cast<std::size_t>(y) * g.width_ + x] != 0;
        // The component this cell's run faces, -1 for a cell in no run.
        const std::int32_t c = occupied ? component(g, f, x + dx, y + dy) : -1;
        if (open >= 0 && c != open_component) {
          runs.push_back({l, open, i - 1, open_component, 0});
          open = -1;
        }
        if (c >= 0 && open < 0) open = i, open_component = c;
        // A run ends at a tile border too.
        if (open >= 0 && i % kTile == kTile - 1) {
          runs.push_back({l, open, i, open_component, 0});
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
  static void mark_covered(Runs& runs) {
    for (int s1 = 0; s1 < 4; ++s1) {
      const bool rows1 = s1 >= 2;
      for (Run& r1 : runs[s1]) {
        if (r1.first != r1.last) continue;
        // The cell's row (for a face of a column run) or column, and its place along it.
        const int line = r1.first, at = r1.line;
        for (const int s2 : rows1 ? std::array{0, 1} : std::array{2, 3}) {
          const Run* r2 = run_at(runs[s2], line, at);
          if (r2 == nullptr) continue;
          const bool at_end = s1 % 2 == 0 ? r2->first == at : r2->last == at;  // left, bottom
          if (r2->line == line && at_end && r2->component == r1.component &&
              (r2->first != r2->last || s2 > s1))
            r1.cover |= 1 << s2;
        }
      }
    }
  }

  // The last run of `runs` (in order of line, then of first cell) that starts on `line` at or
  // before `at`, or on an earlier line; null when there is none.
  static const Run* run_at(const std::vector<Run>& runs, int line, int at) {
    const auto after =
        std::upper_bound(runs.begin(), runs.end(), std::pair{line, at},
                         [](const std::pair<int, int>& p, const Run& r) {
                           return p.first < r.line || (p.first == r.line && p.second < r.first);
                         });
    return after == runs.begin() ? nullptr : &*std::prev(after);
  }

  // The runs into the tiles (runs, start: a counting sort by tile and side), each
  // tile's box (box), and each tile's side in component order (then line and place, as
  // built): a fan takes one component.
  static void bucket_by_tile(const OccupancyGrid& g, FanIndex& f, const Runs& runs) {
    const std::size_t tiles = static_cast<std::size_t>(f.tile_cols) * f.tile_rows;
    f.start.assign(4 * tiles + 1, 0);
    for (int s = 0; s < 4; ++s)
      for (const Run& r : runs[s]) ++f.start[4 * tile_of(s, r, f.tile_cols) + s + 1];
    for (std::size_t i = 1; i < f.start.size(); ++i) f.start[i] += f.start[i - 1];
    f.runs.resize(static_cast<std::size_t>(f.start.back()));
    std::vector<std::int32_t> fill(f.start.begin(), f.start.end() - 1);
    f.box.assign(tiles, CellBox{g.width_, 0, g.height_, 0});
    for (int s = 0; s < 4; ++s) {
      const bool rows = s >= 2;
      for (const Run& r : runs[s]) {
        const std::size_t t = tile_of(s, r, f.tile_cols);
        f.runs[fill[4 * t + s]++] = r;
        CellBox& b = f.box[t];
        const int x0 = rows ? r.first : r.line, x1 = rows ? r.last + 1 : r.line + 1;
        const int y0 = rows ? r.line : r.first, y1 = rows ? r.line + 1 : r.last + 1;
        b = {std::min(b.x0, x0), std::max(b.x1, x1), std::min(b.y0, y0), std::max(b.y1, y1)};
      }
    }
    for (std::size_t i = 0; i + 1 < f.start.size(); ++i)
      std::stable_sort(f.runs.begin() + f.start[i], f.runs.begin() + f.start[i + 1],
                       [](const Run& a, const Run& b) { return a.component < b.component; });
  }
};

void OccupancyGrid::compute_boundary() {
  auto index = std::make_shared<FanIndex>();
  index->free_component = free_components(occupied_, width_, height_);
  index->tile_cols = (width_ + kTile - 1) / kTile;
  index->tile_rows = (height_ + kTile - 1) / kTile;
  // A run is taken by the fans from origins in the component of free cells its cells face (the
  // side's neighbours: one component per run). The least distance of a fan's beam is that of
  // such a run. The walk is in a free cell W of the origin's component until that distance; then
  // it steps into a neighbour of W (whose neighbour facing the walk is W) or passes a corner,
  // touching the two cells beside it: an occupied one faces W, and when both are free (then in
  // W's component) the diagonal cell faces one of them. Either cell is on a side the walk comes
  // from. So the far side of a hollow outline (facing its inside) is left out from outside.
  BoundaryBuild::Runs runs;
  for (int s = 0; s < 4; ++s) BoundaryBuild::collect_side(*this, *index, s, runs[s]);
  BoundaryBuild::mark_covered(runs);
  BoundaryBuild::bucket_by_tile(*this, *index, runs);
  fan_index_ = std::move(index);
}

namespace {

// Each beam cast on its own (OccupancyGrid::cast_ray): what a fan cannot take.
void cast_each_ray(const OccupancyGrid& grid, const Vec2& origin_world, std::span<const Vec2> dirs,
                   double max_range, std::span<double> out) {
  for (std::size_t i = 0; i < dirs.size(); ++i)
    out[i] = grid.cast_ray(origin_world, dirs[i], max_range);
}

// The walk from cell (ix0, iy0) enters or touches (through a corner) cell (x, y) exactly when the
// latest of the events that bring it into the cell's column and row (the boundary quotients
// exit_x(x - sx), exit_y(y - sy); t0 = 0 for the origin's own column or row) is not after the
// earliest of those that take it out (exit_x(x), exit_y(y)): it takes the events in increasing
// order, a tie being a corner step that touches both side cells. That latest event is the
// distance it returns for the cell (its running maximum), and it returns the first occupied
// cell within t_max, whose distance is the least. So the minimum over the occupied cells a fan
// tests is `cast`'s answer to the bit; cells no walk can reach first only need to be left out.
//
// On one axis: the times the walk enters (a) and leaves (b) line c of the cells, from origin
// coordinate oc in line c0 along direction component d; false when it never gets there.
inline bool axis_times(double d, int c, int c0, double oc, double& a, double& b) {
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
}

// The walk's exact test of cell (x, y) for beam k, lowering best[k] to its distance (see
// axis_times). The fan's numbers by value: one load each in the loops over the beams.
struct CellTest {
  const double* dx;
  const double* dy;
  double* best;
  int ix0, iy0;
  double ox, oy, t_max;

  void operator()(int k, int x, int y) const {
    if (best[k] == -kInf) return;
    double ax = 0.0, bx = kInf, ay = 0.0, by = kInf;
    if (!axis_times(dx[k], x, ix0, ox, ax, bx) || !axis_times(dy[k], y, iy0, oy, ay, by)) return;
    const double h = std::max(0.0, std::max(ax, ay));
    if (h <= std::min(bx, by) && h <= t_max && h < best[k]) best[k] = h;
  }
};

// Run [first, last] of side s on line `line` against beam k. The face of the run that facing
// walks cross is the line a = face of axis a (0: x = face, 1: y = face). A walk crosses it with
// the event q = (face - o_a) / d_a, the very quotient it computes, at b = o_b + q d_b on the
// other axis (to within far less than the face's margin). When b is inside the face, away from
// its ends, the walk enters the run's line there, in a cell of the run (or touches one through a
// corner at that event), and it has touched none of the line before: the run's first distance
// is max(0, q) exactly (max(t0, ...) as the walk keeps it). Otherwise (near an end, or entering
// the box through an end) the cells of the run within a cell of floor(b), clamped to the run,
// are tested with the walk's exact test. The run's numbers by value (one load each in the loop
// over the beams, not two).
template <int s>
struct FaceTest {
  CellTest cell;
  int line, first, last;
  double lower;      // the run's lower bound: a beam with a nearer hit needs no test
  double face_oa;    // face - o_a
  double ob;         // o_b
  double inside_lo;  // the face, less its margin at each end
  double inside_hi;
  double t_max;
  const double* da_of;  // the beams' components along axis a and b
  const double* db_of;

  void test_cell(int k, int c) const {
    if constexpr (s >= 2) {
      cell(k, c, line);
    } else {
      cell(k, line, c);
    }
  }

  void operator()(int k) const {
    double* best = cell.best;
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
      for (int c = first; c <= last; ++c) test_cell(k, c);
      return;
    }
    const double lo = first, hi = last;
    const double fb = fan_detail::floor_by_truncation(b);
    const int c0 = static_cast<int>(std::clamp(fb - 1.0, lo, hi));
    const int c1 = static_cast<int>(std::clamp(fb + 1.0, lo, hi));
    for (int c = c0; c <= c1; ++c) test_cell(k, c);
  }
};

// The directions (from the origin) of a box's silhouette corners, seen from outside it: the
// clockwise-most, then the counter-clockwise-most (less than pi from it).
struct Silhouette {
  double cw_x, cw_y, ccw_x, ccw_y;
};

// The silhouette of box [x0, x1] x [y0, y1] from (ox, oy).
Silhouette box_silhouette(double ox, double oy, double x0, double x1, double y0, double y1) {
  const double cw_x = oy < y0 ? x1 : (oy > y1 ? x0 : (ox > x1 ? x1 : x0));
  const double cw_y = ox > x1 ? y1 : (ox < x0 ? y0 : (oy < y0 ? y0 : y1));
  const double ccw_x = oy > y1 ? x1 : (oy < y0 ? x0 : (ox < x0 ? x0 : x1));
  const double ccw_y = ox < x0 ? y1 : (ox > x1 ? y0 : (oy > y1 ? y1 : y0));
  return {cw_x - ox, cw_y - oy, ccw_x - ox, ccw_y - oy};
}

// box_silhouette for the box of a run of side s from an origin the run faces (fewer cases).
template <int s>
Silhouette run_silhouette(double ox, double oy, double x0, double x1, double y0, double y1) {
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
  return {cw_x - ox, cw_y - oy, ccw_x - ox, ccw_y - oy};
}

// Whether coordinate v (cells) lies within a relative kCorner of a cell line.
bool near_cell_line(double v) {
  constexpr double kCorner = 1e-9;  // cells, relative
  return std::abs(v - fan_detail::floor_by_truncation(v + 0.5)) <= kCorner * (1.0 + std::abs(v));
}

// Floor division by kTile: an origin outside the grid may have negative cells.
int tile_floor(int c) {
  return c >= 0 ? c / kTile : -((-c + kTile - 1) / kTile);
}

}  // namespace

// One call of cast_fan on an even fan from an origin it handles (see locate): the beams'
// directions and hits so far (in the caller's FanScratch), and the stages that lower the hits,
// tile ring by tile ring about the origin.
class OccupancyGrid::FanCast {
  using Run = FanIndex::Run;
  using CellBox = FanIndex::CellBox;

 public:
  // Where a fan starts: the origin's cell (of the grid extended by free cells) and whether it
  // lies inside the grid.
  struct Start {
    int ix0 = 0, iy0 = 0;
    bool inside = false;
  };

  // The fan handles an origin `o` (cells) in a free cell of the grid (then `cast` starts its walk
  // at t0 = 0 in cell (ix0, iy0)), and one outside the grid, more than kOutside cells from it,
  // that the grid is within reach of. From outside, `cast` clips each ray to the grid and starts
  // its walk where the ray enters, at t0 in the cell there; everything below takes the walk as
  // if it started at t = 0 in the origin's cell (ix0, iy0) of the grid extended by free cells.
  // Both give a cell of the grid the same entry time where the ray enters the grid through the
  // inside of a border cell's face: that face's quotient is the clipping's t0 (the same division
  // by the same numbers), the entry cell's other line was entered before t0, and the walks take
  // the same events after it. Rays that enter within kCorner of a cell corner go ray by ray
  // (leave_corner_entries). False for an origin the fan does not handle.
  static bool locate(const OccupancyGrid& g, const Vec2& o, Start& start) {
    constexpr double kOutside = 1e-5;        // cells
    constexpr double kMaxOutside = 1 << 24;  // cells: the cell indices below stay exact ints
    start.inside = o.x() >= 0.0 && o.x() < g.width_ && o.y() >= 0.0 && o.y() < g.height_;
    if (start.inside) {
      start.ix0 = clamp_cell(o.x(), g.width_);
      start.iy0 = clamp_cell(o.y(), g.height_);
      return g.occupied_[static_cast<std::size_t>(start.iy0) * g.width_ + start.ix0] == 0;
    }
    const double gx = std::max(-o.x(), o.x() - g.width_), gy = std::max(-o.y(), o.y() - g.height_);
    if (!(std::max(gx, gy) > kOutside) || !(std::abs(o.x()) < kMaxOutside) ||
        !(std::abs(o.y()) < kMaxOutside))
      return false;
    start.ix0 = static_cast<int>(std::floor(o.x()));
    start.iy0 = static_cast<int>(std::floor(o.y()));
    return true;
  }

  FanCast(const OccupancyGrid& grid, const Vec2& o, const Start& start,
          const fan_detail::FanLayout& fan, double t_max, std::size_t n, FanScratch& scratch)
      : grid_(grid),
        index_(*grid.fan_index_),
        o_(o),
        ix0_(start.ix0),
        iy0_(start.iy0),
        // Only runs that walks from the origin's component of free cells can touch first.
        component_(start.inside
                       ? index_.free_component[static_cast<std::size_t>(start.iy0) * grid.width_ +
                                               start.ix0]
                       : 0),
        fan_(fan),
        n_(n),
        t_max_(t_max),
        // Cells whose nearest point is farther than t_max (with room for |dir| and rounding)
        // cannot be reached within t_max.
        reach_(t_max * (1.0 + 1e-5) + 1e-6),
        reach2_(reach_ * reach_),
        // How far inside a face its crossing b must be for the face's own quotient to be the
        // run's distance: far more than b's rounding, 1e-16 (|q| + |o|), for every q <= reach. A
        // crossing farther than t_max (> q) gives no hit either way: every cell of the run is
        // entered after it.
        face_eps_(1e-10 * (1.0 + reach_ + std::max(std::abs(o.x()), std::abs(o.y())))),
        cone_(fan, grid.origin_.theta) {
    if (scratch.dx.size() < n) {
      scratch.dx.resize(n);
      scratch.dy.resize(n);
      scratch.best.resize(n);
    }
    dx_ = scratch.dx.data();
    dy_ = scratch.dy.data();
    best_ = scratch.best.data();
    // A fan narrower than a full turn (a lidar of 180 degrees) leaves out the boxes that lie
    // wholly behind it (see wholly_behind). Every beam is within half_width (+ 1e-8 for the
    // angles' tolerance and the rounding of the directions) of the fan's centre line.
    const double half_width = 0.5 * (fan.n - 1) * fan.step;
    const double behind = std::max(half_width + fan_detail::kFanMargin, 0.5 * kPi);
    cone_test_ = behind < kPi;
    const double centre = fan.first + half_width - grid.origin_.theta;
    cx_ = std::cos(centre);
    cy_ = std::sin(centre);
    cos_behind_ = std::cos(behind);  // <= 0
  }

  // The beams' directions in the grid frame, and their hits so far: none (+inf), or -inf for a
  // beam that is cast ray by ray. The culling assumes a unit direction at the given angle; other
  // beams are cast ray by ray (no test takes them: every lower bound is above -inf).
  void turn_directions(std::span<const Vec2> dirs) {
    // Locals, so that the stores below need not reload them (and the loop vectorises).
    const double c = grid_.cos_yaw_, s = grid_.sin_yaw_;
    double* dx = dx_;
    double* dy = dy_;
    double* best = best_;
    for (std::size_t i = 0; i < n_; ++i) {
      const double x = dirs[i].x(), y = dirs[i].y();
      const double gx = c * x + s * y, gy = -s * x + c * y;
      dx[i] = gx;
      dy[i] = gy;
      const double len2 = gx * gx + gy * gy;
      best[i] = std::abs(len2 - 1.0) <= 1e-6 ? kInf : -kInf;
    }
  }

  // From outside the grid: beams that enter it (`cast`'s clipping) near a cell corner, or not
  // through the inside of a border cell's face, are cast ray by ray (see locate).
  void leave_corner_entries() {
    const Box2 cells{Vec2(0.0, 0.0), Vec2(grid_.width_, grid_.height_)};
    for (std::size_t i = 0; i < n_; ++i) {
      double t0 = 0.0, t1 = t_max_;
      if (best_[i] == -kInf || !clip_ray_to_box(o_, Vec2(dx_[i], dy_[i]), cells, t0, t1)) continue;
      const double px = o_.x() + t0 * dx_[i], py = o_.y() + t0 * dy_[i];
      if (!(px > -0.5 && py > -0.5) || (near_cell_line(px) && near_cell_line(py))) best_[i] = -kInf;
    }
  }

  // The tiles in rings about the origin's tile (ring r: Chebyshev distance r in tiles), nearest
  // first, so that near hits skip the tiles behind them. Every cell of ring r >= 1 is at least
  // (r - 1) * kTile cells from the origin: past the farthest a beam can still reach, stop.
  void rings() const {
    const int tx0 = tile_floor(ix0_), ty0 = tile_floor(iy0_);
    // The farthest any beam can still take a hit (cell units): t_max at first, lowered every
    // fourth ring (the loop costs a few rings' work) and tested at every ring (it only falls).
    double farthest = t_max_;
    for (int ring = 0;; ++ring) {
      if (ring >= 2 && ring % 4 == 0) farthest = farthest_hit();
      if (ring >= 2 && (ring - 1.0) * kTile * (1.0 - 1e-5) > farthest) break;
      const int xa = tx0 - ring, xb = tx0 + ring, ya = ty0 - ring, yb = ty0 + ring;
      if (xa < 0 && ya < 0 && xb >= index_.tile_cols && yb >= index_.tile_rows) break;
      // (One call site, so that the ring's work is one piece of code.)
      for (int e = 0; e < 4; ++e) ring_side(e, xa, xb, ya, yb);
    }
  }

  // Cell units to metres (+inf, no hit, to max_range, which is finite); then the beams marked
  // -inf, the only negative results (but for a max_range of -0), cast ray by ray: in a second
  // pass, so that the first vectorises.
  void write_ranges(const Vec2& origin_world, std::span<const Vec2> dirs, double max_range,
                    std::span<double> out) const {
    const double res = grid_.resolution_;
    const double* best = best_;
    double* result = out.data();
    std::uint64_t signs = 0;
    for (std::size_t i = 0; i < n_; ++i) {
      const double r = std::min(best[i] * res, max_range);
      result[i] = r;
      signs |= std::bit_cast<std::uint64_t>(r);
    }
    if ((signs >> 63) != 0) {
      for (std::size_t i = 0; i < n_; ++i)
        if (best[i] == -kInf) result[i] = grid_.cast_ray(origin_world, dirs[i], max_range);
    }
  }

 private:
  // The farthest any beam not cast ray by ray can still take a hit: its hit so far, or t_max.
  // A beam cast ray by ray (best = -inf) raises nothing. Four lanes at a time (GCC's vector
  // extensions); the maximum is the same in any order.
  double farthest_hit() const {
    using V4d = double __attribute__((vector_size(32)));
    const double* best = best_;
    const double t_max = t_max_;
    V4d f = V4d{} - kInf;
    std::size_t k = 0;
    for (; k + 4 <= n_; k += 4) {
      V4d b;
      std::memcpy(&b, best + k, sizeof b);
      const V4d cap = b < t_max ? b : t_max;
      f = f < cap ? cap : f;
    }
    double f0 = std::max(std::max(f[0], f[1]), std::max(f[2], f[3]));
    for (; k < n_; ++k) f0 = std::max(f0, best[k] < t_max ? best[k] : t_max);
    return f0;
  }

  // Side e of the ring of tiles [xa, xb] x [ya, yb]: the bottom row, the top row, the left
  // column, the right column (without corners), clipped to the grid (a ring about an origin
  // outside the grid may have a side beyond it), passed over at once when the whole side lies
  // beyond reach or behind the fan (a box whose corners are behind is behind).
  void ring_side(int e, int xa, int xb, int ya, int yb) const {
    if ((e == 1 && yb == ya) || (e == 3 && xb == xa)) return;
    int x0 = e == 3 ? xb : xa, x1 = e == 2 ? xa : xb;
    int y0 = e == 0 ? ya : (e == 1 ? yb : ya + 1), y1 = e == 0 ? ya : (e == 1 ? yb : yb - 1);
    x0 = std::max(x0, 0), x1 = std::min(x1, index_.tile_cols - 1);
    y0 = std::max(y0, 0), y1 = std::min(y1, index_.tile_rows - 1);
    if (x0 > x1 || y0 > y1) return;
    const double bx0 = x0 * kTile, bx1 = std::min(x1 * kTile + kTile, grid_.width_);
    const double by0 = y0 * kTile, by1 = std::min(y1 * kTile + kTile, grid_.height_);
    const double gx = std::max({0.0, bx0 - o_.x(), o_.x() - bx1});
    const double gy = std::max({0.0, by0 - o_.y(), o_.y() - by1});
    if (gx * gx + gy * gy > reach2_ || wholly_behind(bx0, bx1, by0, by1)) return;
    for (int ty = y0; ty <= y1; ++ty)
      for (int tx = x0; tx <= x1; ++tx) tile(tx, ty);
  }

  // Tile (tx, ty): its runs of each side, unless no beam may still take a hit from its box.
  void tile(int tx, int ty) const {
    const std::size_t t = static_cast<std::size_t>(ty) * index_.tile_cols + tx;
    if (index_.start[4 * t] == index_.start[4 * t + 4]) return;
    // The box of the tile's runs: every cell a run of it holds is in there.
    const CellBox& b = index_.box[t];
    if (!wanted(b.x0, b.x1, b.y0, b.y1)) return;
    tile_side<0>(t, tx, ty);
    tile_side<1>(t, tx, ty);
    tile_side<2>(t, tx, ty);
    tile_side<3>(t, tx, ty);
  }

  // Whether some beam may still take a hit from a cell of box [x0, x1] x [y0, y1] (the box of a
  // tile's runs): a beam within the box's angular extent whose hit so far (or t_max) is not
  // nearer than the box's lower bound. When none may, `run` would leave every run of the box
  // untested: each of its beams is either outside the run's extent (the run's box is inside),
  // so its walk touches no cell of the run, or sees the run's lower bound (not below the box's)
  // above its hit so far or above t_max, which a hit h >= lower bound cannot beat.
  bool wanted(double x0, double x1, double y0, double y1) const {
    const double gx = std::max({0.0, x0 - o_.x(), o_.x() - x1});
    const double gy = std::max({0.0, y0 - o_.y(), o_.y() - y1});
    const double gap2 = gx * gx + gy * gy;
    if (gap2 > reach2_) return false;
    if (gap2 < 1e-12) return true;
    if (wholly_behind(x0, x1, y0, y1)) return false;
    const double lower = std::sqrt(gap2) * (1.0 - 1e-5);
    // lower <= min(best[k], t_max) for a beam not cast ray by ray (best[k] != -inf): as lower
    // >= 0, the same as lower <= t_max (once) and lower <= best[k].
    if (!(lower <= t_max_)) return false;
    // The beams towards the box (FanCone::for_beams: possibly a few more), until one may.
    const Silhouette c = box_silhouette(o_.x(), o_.y(), x0, x1, y0, y1);
    const double* best = best_;
    return cone_.for_beams(c.cw_x, c.cw_y, c.ccw_x, c.ccw_y,
                           [lower, best](int k) { return lower <= best[k]; });
  }

  // Whether box [x0, x1] x [y0, y1] lies wholly behind a fan narrower than a full turn, without
  // an atan2. The points p (from the origin) more than `behind` >= pi / 2 from the fan's centre
  // line form a convex cone, so a box whose four corners are in it lies in it, and no beam
  // passes through it.
  bool wholly_behind(double x0, double x1, double y0, double y1) const {
    return cone_test_ && corner_behind(x0, y0) && corner_behind(x1, y0) && corner_behind(x0, y1) &&
           corner_behind(x1, y1);
  }

  bool corner_behind(double x, double y) const {
    const double px = x - o_.x(), py = y - o_.y();
    const double along = px * cx_ + py * cy_;
    return along < 0.0 && along * along > cos_behind_ * cos_behind_ * (px * px + py * py);
  }

  // Tile t's runs of side s of the origin's component (together, in component order) that face
  // the origin: side 0 on columns right of the origin's column, 1 on those left of it, 2 on rows
  // above, 3 on rows below. None does when all the tile's lines lie on the wrong side.
  template <int s>
  void tile_side(std::size_t t, int tx, int ty) const {
    if ((s == 0 && tx * kTile + kTile - 1 <= ix0_) || (s == 1 && tx * kTile >= ix0_) ||
        (s == 2 && ty * kTile + kTile - 1 <= iy0_) || (s == 3 && ty * kTile >= iy0_))
      return;
    const Run* r = index_.runs.data() + index_.start[4 * t + s];
    const Run* end = index_.runs.data() + index_.start[4 * t + s + 1];
    while (r != end && r->component < component_) ++r;
    for (; r != end && r->component == component_; ++r) {
      const bool faces = s == 0   ? r->line > ix0_
                         : s == 1 ? r->line < ix0_
                         : s == 2 ? r->line > iy0_
                                  : r->line < iy0_;
      if (!faces) continue;
      if (r->cover != 0) {
        // Left out when a run that tests its cell for it faces the origin too.
        const int cx = s >= 2 ? r->first : r->line, cy = s >= 2 ? r->line : r->first;
        if (((r->cover & 1) && cx > ix0_) || ((r->cover & 2) && cx < ix0_) ||
            ((r->cover & 4) && cy > iy0_) || ((r->cover & 8) && cy < iy0_))
          continue;
      }
      run<s>(*r);
    }
  }

  // Run `r` of side s against the beams within its box's angular extent (FaceTest).
  template <int s>
  void run(const Run& r) const {
    constexpr bool rows = s >= 2;
    const int l = r.line;
    const double x0 = rows ? r.first : l, x1 = rows ? r.last + 1.0 : l + 1.0;
    const double y0 = rows ? l : r.first, y1 = rows ? l + 1.0 : r.last + 1.0;
    const double ox = o_.x(), oy = o_.y();
    // The origin is beyond the run's side: left of x0 for side 0 (its column is left of the
    // run's), right of x1 (or on it) for side 1, below y0 for 2, above y1 (or on it) for 3.
    const double gx = s == 0 ? x0 - ox : (s == 1 ? ox - x1 : std::max({0.0, x0 - ox, ox - x1}));
    const double gy = s == 2 ? y0 - oy : (s == 3 ? oy - y1 : std::max({0.0, y0 - oy, oy - y1}));
    const double gap2 = gx * gx + gy * gy;
    if (gap2 > reach2_) return;
    // A walk enters the box no earlier than its distance (|dir| <= 1 + 1e-6); a beam that
    // already has a nearer hit needs no test (the minimum is the same).
    const double lower = std::sqrt(gap2) * (1.0 - 1e-5);
    constexpr int axis = rows ? 1 : 0;
    const double face = (s == 0 || s == 2) ? l : l + 1.0;
    const double oa = o_[axis], ob = o_[1 - axis];
    const double lo = r.first, hi = r.last;
    const FaceTest<s> each{
        CellTest{dx_, dy_, best_, ix0_, iy0_, ox, oy, t_max_},
        l,
        r.first,
        r.last,
        lower,
        face - oa,
        ob,
        lo + face_eps_,
        hi + 1.0 - face_eps_,
        t_max_,
        axis == 0 ? dx_ : dy_,
        axis == 0 ? dy_ : dx_,
    };
    if (gap2 < 1e-12) {
      for (int k = 0; k < fan_.n; ++k) each(k);
      return;
    }
    const Silhouette c = run_silhouette<s>(ox, oy, x0, x1, y0, y1);
    cone_.for_beams(c.cw_x, c.cw_y, c.ccw_x, c.ccw_y, each);
  }

  const OccupancyGrid& grid_;
  const FanIndex& index_;
  const Vec2 o_;  // the origin, cells of the grid frame
  const int ix0_, iy0_;
  const std::int32_t component_;
  const fan_detail::FanLayout fan_;
  const std::size_t n_;
  const double t_max_;
  const double reach_;
  const double reach2_;
  const double face_eps_;
  const fan_detail::FanCone cone_;
  double* dx_;
  double* dy_;
  double* best_;
  // wholly_behind's cone: whether it applies, the fan's centre line, cos of its half-angle.
  bool cone_test_;
  double cx_, cy_, cos_behind_;
};

// The fan's work is the bulk of a lidar robot's step, so it gets an x86-64-v3 clone with the
// same results; BM_CaveGridCastFan180 (bench/grid_bench.cpp) decides whether the clone pays.
// The clone's `flatten` inlines every stage of FanCast into it.
FLOORNAV_ISA_CLONES
void OccupancyGrid::cast_fan(const Vec2& origin_world, std::span<const Vec2> dirs,
                             std::span<const double> angles, double max_range,
                             std::span<double> out, FanScratch& scratch) const {
  const std::size_t n = dirs.size();
  // What `cast` computes first, to the bit.
  const Vec2 o = to_grid(origin_world) / resolution_;
  FanCast::Start start;
  if (n < 2 || !is_finite(o) || !(max_range >= 0.0) || !std::isfinite(max_range) ||
      !FanCast::locate(*this, o, start))
    return cast_each_ray(*this, origin_world, dirs, max_range, out);
  const std::optional<fan_detail::FanLayout> fan = fan_detail::even_fan(angles);
  if (!fan) return cast_each_ray(*this, origin_world, dirs, max_range, out);

  FanCast cast(*this, o, start, *fan, max_range / resolution_, n, scratch);
  cast.turn_directions(dirs);
  if (!start.inside) cast.leave_corner_entries();
  cast.rings();
  cast.write_ranges(origin_world, dirs, max_range, out);
}

void OccupancyGrid::cast_fan(const Vec2& origin_world, std::span<const Vec2> dirs,
                             std::span<const double> angles, double max_range,
                             std::span<double> out) const {
  FanScratch scratch;
  cast_fan(origin_world, dirs, angles, max_range, out, scratch);
}

}  // namespace floornav
