#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "cell_index.hpp"
#include "floornav/world/lower_envelope.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "grid_walk.hpp"

// OccupancyGrid's distance transform, computed once: for every cell the nearest occupied cell
// (an exact Euclidean feature transform), and from it the clearance queries and the free runs
// that the ray walk jumps by.

namespace floornav {
namespace {

using cell_detail::clamp_cell;
using grid_detail::kFreeRunUnits;
using grid_detail::kInf;
using grid_detail::kMaxFreeRun;

/// Distance along one axis from coordinate `p` (cell units) to the slab [i, i + 1].
inline double axis_gap(double p, int i) {
  const double d = std::abs(i + 0.5 - p) - 0.5;
  return d > 0.0 ? d : 0.0;
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
    const auto is_site = [&](int q) {
      const std::int32_t code = column[row + q];
      if (code < 0) return false;
      const std::int64_t dy = y - (code >> 1);
      f[q] = dy * dy;
      return true;
    };
    // Intersection of the parabolas at r and q, written so that no term exceeds 2^53.
    const auto intersect = [&](int r, int q) {
      return static_cast<double>(f[q] - f[r]) * inv_twice[q - r] + 0.5 * (q + r);
    };
    const auto emit = [&](int x, int q) { nearest[row + x] = (column[row + q] >> 1) * width + q; };
    // Rows without a site (the whole grid is free) keep -1.
    envelope_detail::lower_envelope(width, is_site, intersect, emit, v.data(), z.data());
  }
}

}  // namespace

void OccupancyGrid::compute_distance_transform() {
  compute_column_nearest(width_, height_, occupied_, column_nearest_);
  compute_nearest(width_, height_, column_nearest_, nearest_);
  compute_free_run();
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

std::int32_t OccupancyGrid::nearest_occupied_index(int ix, int iy) const {
  if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return -1;
  return nearest_[static_cast<std::size_t>(iy) * width_ + ix];
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

bool OccupancyGrid::in_occupied_cell(double px, double py) const {
  if (!(px >= 0.0 && py >= 0.0 && px < width_ && py < height_)) return false;
  const std::size_t row = static_cast<std::size_t>(static_cast<int>(py)) * width_;
  return occupied_[row + static_cast<int>(px)] != 0;
}

double OccupancyGrid::clearance(const Vec2& p) const {
  if (occupied_count_ == 0) return kInf;
  const Vec2 g = to_grid(p) / resolution_;
  if (!is_finite(g)) return std::numeric_limits<double>::quiet_NaN();
  const double px = g.x();
  const double py = g.y();
  if (in_occupied_cell(px, py)) {
    // Inside: minus the distance to the cell's own border (a lower bound on the depth when
    // neighbouring cells are occupied too).
    const int ix = static_cast<int>(px);
    const int iy = static_cast<int>(py);
    const double depth = std::min(std::min(px - ix, ix + 1 - px), std::min(py - iy, iy + 1 - py));
    return -depth * resolution_;
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
  if (in_occupied_cell(px, py)) {
    // The point of the cell's own border that `clearance` measures to.
    const int ix = static_cast<int>(px);
    const int iy = static_cast<int>(py);
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

}  // namespace floornav
