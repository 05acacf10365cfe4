#include "floornav/world/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "fan_layout.hpp"

namespace floornav {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// free_run_ counts in 1/16 cell, up to 4096 cells; a jump shorter than a cell is not worth it.
constexpr double kFreeRunUnits = 16.0;
constexpr std::uint16_t kMaxFreeRun = 65535;
constexpr int kMinJump = 16;

/// Largest grid the int32 cell indices (and the 2 * row + 1 column code) can address.
constexpr std::size_t kMaxCells = std::size_t{1} << 30;

/// Distance along one axis from coordinate `p` (cell units) to the slab [i, i + 1].
inline double axis_gap(double p, int i) {
  const double d = std::abs(i + 0.5 - p) - 0.5;
  return d > 0.0 ? d : 0.0;
}

/// `floor(v)` clamped to [0, n - 1], safe for any finite `v`.
inline int clamp_cell(double v, int n) {
  const double f = std::floor(v);
  if (!(f > 0.0)) return 0;
  if (f >= n - 1) return n - 1;
  return static_cast<int>(f);
}

/// Pass 1 of the feature transform, along columns but sweeping rows so that memory is read in
/// order: for each cell, the nearest occupied row in its column, coded as 2 * r + tie (see
/// `column_nearest_`).
void compute_column_nearest(int width, int height, const std::vector<std::uint8_t>& occupied,
                            std::vector<std::int32_t>& column) {
  const std::size_t w = static_cast<std::size_t>(width);
  column.assign(w * static_cast<std::size_t>(height), -1);
  std::vector<std::int32_t> last(w, -1);  // nearest occupied row <= y, per column
  for (int y = 0; y < height; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * w;
    for (std::size_t x = 0; x < w; ++x) {
      if (occupied[row + x] != 0) last[x] = y;
      column[row + x] = last[x];
    }
  }
  std::vector<std::int32_t> next(w, -1);  // nearest occupied row >= y, per column
  for (int y = height - 1; y >= 0; --y) {
    const std::size_t row = static_cast<std::size_t>(y) * w;
    for (std::size_t x = 0; x < w; ++x) {
      if (occupied[row + x] != 0) next[x] = y;
      const std::int32_t below = column[row + x];
      const std::int32_t above = next[x];
      std::int32_t code = -1;
      if (below < 0 && above >= 0) {
        code = 2 * above;
      } else if (above < 0 && below >= 0) {
        code = 2 * below;
      } else if (below >= 0) {
        const std::int32_t db = y - below;
        const std::int32_t da = above - y;
        if (db < da) {
          code = 2 * below;
        } else if (da < db) {
          code = 2 * above;
        } else {
          code = 2 * below + (da > 0 ? 1 : 0);
        }
      }
      column[row + x] = code;
    }
  }
}

/// Pass 2 (Felzenszwalb & Huttenlocher, "Distance Transforms of Sampled Functions", 2012): along
/// each row, the lower envelope of the parabolas (x - q)^2 + f(q), f(q) = squared distance from
/// (q, y) to its column's nearest occupied cell, carrying the argmin. O(width) per row.
void compute_nearest(int width, int height, const std::vector<std::int32_t>& column,
                     std::vector<std::int32_t>& nearest) {
  const std::size_t w = static_cast<std::size_t>(width);
  nearest.assign(w * static_cast<std::size_t>(height), -1);
  std::vector<std::int32_t> v(w);  // apexes of the envelope's parabolas
  std::vector<double> z(w + 1);    // where parabola k starts to be the lowest
  std::vector<std::int64_t> f(w);  // squared column distance per q
  // 1 / (2 d) for d = q - r in [1, width): a multiplication instead of a division per step (the
  // transform's hot spot). Distinct intersections of integer parabolas differ by at least
  // 1 / (4 width^2), far above the rounding this adds for widths up to ~2^20, so the envelope is
  // unchanged. (Beyond that a near-tie may pick a cell that is nearer by a rounding error only.)
  std::vector<double> inv_twice(w);
  for (std::size_t d = 1; d < w; ++d) inv_twice[d] = 1.0 / (2.0 * static_cast<double>(d));
  for (int y = 0; y < height; ++y) {
    const std::size_t row = static_cast<std::size_t>(y) * w;
    int k = -1;
    for (int q = 0; q < width; ++q) {
      const std::int32_t code = column[row + q];
      if (code < 0) continue;
      const std::int64_t dy = y - (code >> 1);
      f[q] = dy * dy;
      if (k < 0) {
        k = 0;
        v[0] = q;
        z[0] = -kInf;
        z[1] = kInf;
        continue;
      }
      double s = 0.0;
      for (;;) {
        const int r = v[k];
        // Intersection of the parabolas at r and q, written so that no term exceeds 2^53.
        s = static_cast<double>(f[q] - f[r]) * inv_twice[q - r] + 0.5 * (q + r);
        if (s <= z[k]) {
          --k;  // z[0] = -inf stops this at k = 0
        } else {
          break;
        }
      }
      ++k;
      v[k] = q;
      z[k] = s;
      z[k + 1] = kInf;
    }
    if (k < 0) continue;  // the whole grid is free
    int j = 0;
    for (int x = 0; x < width; ++x) {
      while (z[j + 1] < x) ++j;
      const int q = v[j];
      nearest[row + x] = (column[row + q] >> 1) * width + q;
    }
  }
}

}  // namespace

OccupancyGrid::OccupancyGrid(int width, int height, double resolution, Pose2 origin,
                             std::vector<std::uint8_t> occupied)
    : width_(width),
      height_(height),
      resolution_(resolution),
      origin_(origin),
      occupied_(std::move(occupied)) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("OccupancyGrid: width and height must be positive, got " +
                                std::to_string(width) + " x " + std::to_string(height));
  }
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("OccupancyGrid: resolution must be positive and finite, got " +
                                std::to_string(resolution));
  }
  if (!origin.is_finite()) throw std::invalid_argument("OccupancyGrid: origin is not finite");
  const std::size_t cells = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (cells > kMaxCells) {
    throw std::invalid_argument("OccupancyGrid: " + std::to_string(cells) +
                                " cells is more than the 2^30 supported");
  }
  if (occupied_.size() != cells) {
    throw std::invalid_argument("OccupancyGrid: expected " + std::to_string(cells) +
                                " cells (width * height), got " + std::to_string(occupied_.size()));
  }
  occupied_count_ = static_cast<std::size_t>(
      std::count_if(occupied_.begin(), occupied_.end(), [](std::uint8_t c) { return c != 0; }));
  cos_yaw_ = std::cos(origin_.theta);
  sin_yaw_ = std::sin(origin_.theta);
  compute_column_nearest(width_, height_, occupied_, column_nearest_);
  compute_nearest(width_, height_, column_nearest_, nearest_);
  compute_free_run();
  compute_boundary();
}

void OccupancyGrid::compute_boundary() {
  const auto free_at = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < width_ && y < height_ &&
           occupied_[static_cast<std::size_t>(y) * width_ + x] == 0;
  };
  const auto occupied_at = [&](int x, int y) {
    return occupied_[static_cast<std::size_t>(y) * width_ + x] != 0;
  };
  for (int s = 0; s < 4; ++s) {
    const bool rows = s >= 2;  // runs along rows (of columns)
    const int lines = rows ? height_ : width_;
    const int along = rows ? width_ : height_;
    const int dx = s == 0 ? -1 : (s == 1 ? 1 : 0);
    const int dy = s == 2 ? -1 : (s == 3 ? 1 : 0);
    runs_[s].clear();
    run_start_[s].assign(static_cast<std::size_t>(lines) + 1, 0);
    for (int l = 0; l < lines; ++l) {
      run_start_[s][l] = static_cast<std::int32_t>(runs_[s].size());
      int open = -1;
      for (int i = 0; i <= along; ++i) {
        const int x = rows ? i : l, y = rows ? l : i;
        const bool in = i < along && occupied_at(x, y) && free_at(x + dx, y + dy);
        if (in && open < 0) open = i;
        if (!in && open >= 0) {
          runs_[s].push_back({open, i - 1});
          open = -1;
        }
      }
    }
    run_start_[s][lines] = static_cast<std::int32_t>(runs_[s].size());
  }
}

void OccupancyGrid::compute_free_run() {
  // A ray point in cell c is within sqrt(2)/2 of c's centre, and a point of an occupied square
  // within sqrt(2)/2 of that square's centre, at least D (the nearest occupied centre's
  // distance) from c's centre. So a ray entering c runs D - sqrt(2) cells before it can touch an
  // occupied square; 1.5 instead of sqrt(2) leaves room for rounding. In 1/16 cell, rounded
  // down.
  free_run_.assign(occupied_.size(), kMaxFreeRun);
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      const std::size_t c = static_cast<std::size_t>(y) * width_ + x;
      const std::int32_t n = nearest_[c];
      if (n < 0) continue;
      const double dx = n % width_ - x;
      const double dy = n / width_ - y;
      const double run = std::floor((std::sqrt(dx * dx + dy * dy) - 1.5) * kFreeRunUnits);
      free_run_[c] = static_cast<std::uint16_t>(std::clamp(run, 0.0, double{kMaxFreeRun}));
    }
  }
}

bool OccupancyGrid::occupied(int ix, int iy) const {
  if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return false;
  return occupied_[static_cast<std::size_t>(iy) * width_ + ix] != 0;
}

std::size_t OccupancyGrid::occupied_count() const {
  return occupied_count_;
}

std::int32_t OccupancyGrid::nearest_occupied_index(int ix, int iy) const {
  if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return -1;
  return nearest_[static_cast<std::size_t>(iy) * width_ + ix];
}

Vec2 OccupancyGrid::to_grid(const Vec2& world) const {
  const double dx = world.x() - origin_.position.x();
  const double dy = world.y() - origin_.position.y();
  return {cos_yaw_ * dx + sin_yaw_ * dy, -sin_yaw_ * dx + cos_yaw_ * dy};
}

Vec2 OccupancyGrid::to_world(const Vec2& grid) const {
  return {origin_.position.x() + cos_yaw_ * grid.x() - sin_yaw_ * grid.y(),
          origin_.position.y() + sin_yaw_ * grid.x() + cos_yaw_ * grid.y()};
}

double OccupancyGrid::cast_ray(const Vec2& origin_world, const Vec2& dir, double max_range) const {
  return cast(origin_world, dir, max_range, true);
}

namespace {

// Per-thread scratch of OccupancyGrid::cast_fan: it only grows.
struct GridFanScratch {
  std::vector<double> dx, dy, best;
};

GridFanScratch& grid_fan_scratch(std::size_t n) {
  thread_local GridFanScratch s;
  if (s.dx.size() < n) {
    s.dx.resize(n);
    s.dy.resize(n);
    s.best.resize(n);
  }
  return s;
}

}  // namespace

void OccupancyGrid::cast_fan(const Vec2& origin_world, std::span<const Vec2> dirs,
                             std::span<const double> angles, double max_range,
                             std::span<double> out) const {
  const std::size_t n = dirs.size();
  const auto ray_by_ray = [&] {
    for (std::size_t i = 0; i < n; ++i) out[i] = cast_ray(origin_world, dirs[i], max_range);
  };
  // What `cast` computes first, to the bit.
  const Vec2 o = to_grid(origin_world) / resolution_;
  if (n < 2 || !is_finite(o) || !(max_range >= 0.0) || !std::isfinite(max_range)) {
    return ray_by_ray();
  }
  // The fan handles an origin inside the grid, in a free cell (then `cast` starts its walk at
  // t0 = 0 in cell (ix0, iy0)).
  if (!(o.x() >= 0.0 && o.x() < width_ && o.y() >= 0.0 && o.y() < height_)) return ray_by_ray();
  const int ix0 = clamp_cell(o.x(), width_);
  const int iy0 = clamp_cell(o.y(), height_);
  if (occupied_[static_cast<std::size_t>(iy0) * width_ + ix0] != 0) return ray_by_ray();
  const std::optional<fan_detail::FanLayout> fan = fan_detail::even_fan(angles);
  if (!fan) return ray_by_ray();
  const double t_max = max_range / resolution_;

  GridFanScratch& scratch = grid_fan_scratch(n);
  double* dx = scratch.dx.data();
  double* dy = scratch.dy.data();
  double* best = scratch.best.data();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2& dir = dirs[i];
    dx[i] = cos_yaw_ * dir.x() + sin_yaw_ * dir.y();
    dy[i] = -sin_yaw_ * dir.x() + cos_yaw_ * dir.y();
    // The culling below assumes a unit direction at the given angle; other beams are cast ray
    // by ray, marked by best = -inf (no test takes them: every lower bound is above).
    const double len2 = dx[i] * dx[i] + dy[i] * dy[i];
    best[i] = std::abs(len2 - 1.0) <= 1e-6 ? kInf : -kInf;
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
  const auto test = [&](int k, int x, int y) {
    if (best[k] == -kInf) return;
    double ax = 0.0, bx = kInf, ay = 0.0, by = kInf;
    if (!axis_times(dx[k], x, ix0, o.x(), ax, bx) || !axis_times(dy[k], y, iy0, o.y(), ay, by))
      return;
    const double h = std::max(0.0, std::max(ax, ay));
    if (h <= std::min(bx, by) && h <= t_max && h < best[k]) best[k] = h;
  };

  // Cells whose nearest point is farther than t_max (with room for |dir| and rounding) cannot
  // be reached within t_max.
  const double reach = t_max * (1.0 + 1e-5) + 1e-6;
  const double reach2 = reach * reach;
  const double yaw = origin_.theta;
  // Run `r` of side `s` on line `l`: the box [x0, x1] x [y0, y1] of its cells.
  const auto run = [&](auto side, int l, const Run& r) {
    constexpr int s = decltype(side)::value;
    constexpr bool rows = s >= 2;
    const double x0 = rows ? r.first : l, x1 = rows ? r.last + 1.0 : l + 1.0;
    const double y0 = rows ? l : r.first, y1 = rows ? l + 1.0 : r.last + 1.0;
    const double gx = std::max({0.0, x0 - o.x(), o.x() - x1});
    const double gy = std::max({0.0, y0 - o.y(), o.y() - y1});
    const double gap2 = gx * gx + gy * gy;
    if (gap2 > reach2) return;
    // A walk enters the box no earlier than its distance (|dir| <= 1 + 1e-6); a beam that
    // already has a nearer hit needs no test (the minimum is the same).
    const double lower = std::sqrt(gap2) * (1.0 - 1e-5);
    // The face of the run that facing walks cross: the line a = face of axis a (0: x = face,
    // 1: y = face). A walk crosses it with the event q = (face - o_a) / d_a, the very quotient it
    // computes, at b = o_b + q d_b on the other axis (to within far less than eps). When b is
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
    const auto each = [&](int k) {
      if (lower > best[k]) return;
      const double da = axis == 0 ? dx[k] : dy[k], db = axis == 0 ? dy[k] : dx[k];
      if constexpr (s == 0 || s == 2) {
        if (!(da > 0.0)) return;  // moving away from the face
      } else {
        if (!(da < 0.0)) return;
      }
      const double q = (face - oa) / da;
      const double b = ob + q * db;
      const double eps = 1e-10 * (1.0 + std::abs(q) + std::abs(ob));
      if (b >= lo + eps && b <= hi + 1.0 - eps) {
        const double h = std::max(0.0, q);
        if (h <= t_max && h < best[k]) best[k] = h;
        return;
      }
      if (!(b == b)) {
        for (int c = r.first; c <= r.last; ++c) cell_test(k, c);
        return;
      }
      const double fb = std::floor(b);
      const int c0 = static_cast<int>(std::clamp(fb - 1.0, lo, hi));
      const int c1 = static_cast<int>(std::clamp(fb + 1.0, lo, hi));
      for (int c = c0; c <= c1; ++c) cell_test(k, c);
    };
    if (gap2 < 1e-12) {
      for (int k = 0; k < fan->n; ++k) each(k);
      return;
    }
    // The box's angular extent, from its silhouette corners as seen from the origin (outside
    // the box): the clockwise-most one, then counter-clockwise (less than pi) to the other.
    const double ox = o.x(), oy = o.y();
    const double cw_x = oy < y0 ? x1 : (oy > y1 ? x0 : (ox > x1 ? x1 : x0));
    const double cw_y = ox > x1 ? y1 : (ox < x0 ? y0 : (oy < y0 ? y0 : y1));
    const double ccw_x = oy > y1 ? x1 : (oy < y0 ? x0 : (ox < x0 ? x0 : x1));
    const double ccw_y = ox < x0 ? y1 : (ox > x1 ? y0 : (oy > y1 ? y1 : y0));
    const double a_cw = fan_detail::coarse_atan2(cw_y - oy, cw_x - ox);
    double width = fan_detail::coarse_atan2(ccw_y - oy, ccw_x - ox) - a_cw;
    if (width < 0.0) width += fan_detail::kTwoPi;
    const double m = fan_detail::kFanMargin;
    fan_detail::for_beams_in(*fan, a_cw + yaw - m, width + 2.0 * m, each);
  };
  // Only runs whose side faces the origin: side 0 on columns right of the origin's column, 1 on
  // those left of it, 2 on rows above, 3 on rows below. Nearest lines first.
  const auto line = [&](auto side, int l) {
    constexpr int s = decltype(side)::value;
    // The runs of the line that overlap the reach's span along it (they are disjoint and in
    // order, so their ends are in order too).
    const double along = s >= 2 ? o.x() : o.y();
    const double a_lo = along - reach - 1.0, a_hi = along + reach + 1.0;
    const Run* first = runs_[s].data() + run_start_[s][l];
    const Run* last = runs_[s].data() + run_start_[s][l + 1];
    first = std::partition_point(first, last, [&](const Run& r) { return r.last < a_lo; });
    for (; first != last && first->first <= a_hi; ++first) run(side, l, *first);
  };
  const int reach_cells = static_cast<int>(std::min(reach + 2.0, 1e9));
  for (int j = 1; j <= reach_cells; ++j) {
    bool any = false;
    if (ix0 + j < width_) line(std::integral_constant<int, 0>{}, ix0 + j), any = true;
    if (ix0 - j >= 0) line(std::integral_constant<int, 1>{}, ix0 - j), any = true;
    if (iy0 + j < height_) line(std::integral_constant<int, 2>{}, iy0 + j), any = true;
    if (iy0 - j >= 0) line(std::integral_constant<int, 3>{}, iy0 - j), any = true;
    if (!any) break;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (best[i] == -kInf) {
      out[i] = cast_ray(origin_world, dirs[i], max_range);
    } else {
      out[i] = best[i] < kInf ? std::min(best[i] * resolution_, max_range) : max_range;
    }
  }
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
  const double hi[2] = {static_cast<double>(width_), static_cast<double>(height_)};
  const bool inside = o.x() >= 0.0 && o.x() < hi[0] && o.y() >= 0.0 && o.y() < hi[1];
  for (int a = 0; a < 2 && !(skip && inside); ++a) {
    if (d[a] == 0.0) {
      if (!(o[a] >= 0.0 && o[a] < hi[a])) return max_range;
      continue;
    }
    double ta = (0.0 - o[a]) / d[a];
    double tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (t0 > t1) return max_range;

  int ix = clamp_cell(t0 > 0.0 ? o.x() + t0 * d.x() : o.x(), width_);
  int iy = clamp_cell(t0 > 0.0 ? o.y() + t0 * d.y() : o.y(), height_);
  const int sx = d.x() > 0.0 ? 1 : (d.x() < 0.0 ? -1 : 0);
  const int sy = d.y() > 0.0 ? 1 : (d.y() < 0.0 ? -1 : 0);
  // Amanatides & Woo, "A Fast Voxel Traversal Algorithm for Ray Tracing" (1987). Each boundary
  // time is computed afresh from the integer boundary and the ray's origin, so no error
  // accumulates along long rays. The time the walk leaves column i (row i):
  const auto exit_x = [&](int i) {
    return sx > 0 ? (i + 1 - o.x()) / d.x() : (sx < 0 ? (i - o.x()) / d.x() : kInf);
  };
  const auto exit_y = [&](int i) {
    return sy > 0 ? (i + 1 - o.y()) / d.y() : (sy < 0 ? (i - o.y()) / d.y() : kInf);
  };
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
    const double tx = exit_x(ix);
    const double ty = exit_y(iy);
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
  const auto exit_x = [&](int i) {
    return sx > 0 ? (i + 1 - o.x()) / d.x() : (sx < 0 ? (i - o.x()) / d.x() : kInf);
  };
  const auto exit_y = [&](int i) {
    return sy > 0 ? (i + 1 - o.y()) / d.y() : (sy < 0 ? (i - o.y()) / d.y() : kInf);
  };
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
      // exit_x(i) < target, exactly; `near` is near_x(i).
      const auto x_before = [&](int i, double near) {
        if (std::abs(near - target) > kRel * target) return near < target;
        return exit_x(i) < target;
      };
      const auto y_before = [&](int i, double near) {
        if (std::abs(near - target) > kRel * target) return near < target;
        return exit_y(i) < target;
      };
      int jx = ix, jy = iy;
      double entered = t;
      if (sx != 0 && x_before(ix, tx)) {
        const double guess = std::floor(o.x() + target * d.x());
        int g = guess * sx > (ix + sx) * sx ? static_cast<int>(guess) : ix + sx;
        double near = near_x(g);
        while (x_before(g, near)) near = near_x(g += sx);
        for (double prev; g - sx != ix && !x_before(g - sx, prev = near_x(g - sx)); near = prev)
          g -= sx;
        jx = g;
        tx = near;
        entered = std::max(entered, near_x(jx - sx));
      }
      if (sy != 0 && y_before(iy, ty)) {
        const double guess = std::floor(o.y() + target * d.y());
        int g = guess * sy > (iy + sy) * sy ? static_cast<int>(guess) : iy + sy;
        double near = near_y(g);
        while (y_before(g, near)) near = near_y(g += sy);
        for (double prev; g - sy != iy && !y_before(g - sy, prev = near_y(g - sy)); near = prev)
          g -= sy;
        jy = g;
        ty = near;
        entered = std::max(entered, near_y(jy - sy));
      }
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

double OccupancyGrid::nearest_square(double px, double py, std::int32_t* cell) const {
  *cell = -1;
  if (occupied_count_ == 0) return kInf;
  const int cx = clamp_cell(px, width_);
  const int cy = clamp_cell(py, height_);
  double best = kInf;
  auto consider_cell = [&](std::int32_t index) {
    if (index < 0) return;
    const int ox = index % width_;
    const int oy = index / width_;
    const double gx = axis_gap(px, ox);
    const double gy = axis_gap(py, oy);
    const double d2 = gx * gx + gy * gy;
    if (d2 < best) {
      best = d2;
      *cell = index;
    }
  };
  // Seed: the nearest-centre cells of p's cell and its 8 neighbours. This is almost always the
  // answer already, but not provably (ties in the transform, and the square metric differs from
  // the centre metric), so it is only an upper bound for the exact scan below.
  for (int ny = std::max(cy - 1, 0); ny <= std::min(cy + 1, height_ - 1); ++ny) {
    for (int nx = std::max(cx - 1, 0); nx <= std::min(cx + 1, width_ - 1); ++nx) {
      consider_cell(nearest_[static_cast<std::size_t>(ny) * width_ + nx]);
    }
  }
  // Exact scan over columns, outwards from cx. In column x the nearest occupied square to p is
  // the column's nearest occupied row to row cy (either one on a tie): the vertical gap to a
  // row's slab is monotone in the row distance, and p lies in row cy (or beyond the grid's edge
  // next to it). The horizontal gap grows with |x - cx|, so a side stops once it alone reaches
  // the best distance. Cost: O(clearance / resolution) columns, read contiguously.
  const std::int32_t* codes = column_nearest_.data() + static_cast<std::size_t>(cy) * width_;
  auto scan_column = [&](int x) {
    const double gx = axis_gap(px, x);
    const double gx2 = gx * gx;
    if (gx2 >= best) return false;
    const std::int32_t code = codes[x];
    if (code < 0) return true;
    int r = code >> 1;
    double gy = axis_gap(py, r);
    if ((code & 1) != 0) {
      const int other = 2 * cy - r;
      const double g_other = axis_gap(py, other);
      if (g_other < gy) {
        gy = g_other;
        r = other;
      }
    }
    const double d2 = gx2 + gy * gy;
    if (d2 < best) {
      best = d2;
      *cell = r * width_ + x;
    }
    return true;
  };
  for (int x = cx; x < width_ && scan_column(x); ++x) {
  }
  for (int x = cx - 1; x >= 0 && scan_column(x); --x) {
  }
  return best;
}

double OccupancyGrid::clearance(const Vec2& p) const {
  if (occupied_count_ == 0) return kInf;
  const Vec2 g = to_grid(p) / resolution_;
  if (!is_finite(g)) return std::numeric_limits<double>::quiet_NaN();
  const double px = g.x();
  const double py = g.y();
  if (px >= 0.0 && py >= 0.0 && px < width_ && py < height_) {
    const int ix = static_cast<int>(px);
    const int iy = static_cast<int>(py);
    if (occupied_[static_cast<std::size_t>(iy) * width_ + ix] != 0) {
      // Inside: minus the distance to the cell's own border (a lower bound on the depth when
      // neighbouring cells are occupied too).
      const double depth = std::min(std::min(px - ix, ix + 1 - px), std::min(py - iy, iy + 1 - py));
      return -depth * resolution_;
    }
  }
  std::int32_t cell = -1;
  return std::sqrt(nearest_square(px, py, &cell)) * resolution_;
}

bool OccupancyGrid::nearest_occupied_point(const Vec2& p, Vec2* out) const {
  if (occupied_count_ == 0) return false;
  const Vec2 g = to_grid(p) / resolution_;
  if (!is_finite(g)) return false;
  const double px = g.x();
  const double py = g.y();
  if (px >= 0.0 && py >= 0.0 && px < width_ && py < height_) {
    const int ix = static_cast<int>(px);
    const int iy = static_cast<int>(py);
    if (occupied_[static_cast<std::size_t>(iy) * width_ + ix] != 0) {
      // The point of the cell's own border that `clearance` measures to.
      const double gaps[4] = {px - ix, ix + 1 - px, py - iy, iy + 1 - py};
      const int k = static_cast<int>(std::min_element(gaps, gaps + 4) - gaps);
      Vec2 q(px, py);
      if (k == 0) q.x() = ix;
      if (k == 1) q.x() = ix + 1;
      if (k == 2) q.y() = iy;
      if (k == 3) q.y() = iy + 1;
      *out = to_world(q * resolution_);
      return true;
    }
  }
  std::int32_t cell = -1;
  nearest_square(px, py, &cell);
  if (cell < 0) return false;
  const int ox = cell % width_;
  const int oy = cell / width_;
  const Vec2 q(std::clamp(px, static_cast<double>(ox), ox + 1.0),
               std::clamp(py, static_cast<double>(oy), oy + 1.0));
  *out = to_world(q * resolution_);
  return true;
}

void OccupancyGrid::world_extent(Vec2* min, Vec2* max) const {
  const double w = width_ * resolution_;
  const double h = height_ * resolution_;
  const Vec2 corners[4] = {to_world({0.0, 0.0}), to_world({w, 0.0}), to_world({0.0, h}),
                           to_world({w, h})};
  *min = corners[0];
  *max = corners[0];
  for (const Vec2& c : corners) {
    *min = min->cwiseMin(c);
    *max = max->cwiseMax(c);
  }
}

}  // namespace floornav
