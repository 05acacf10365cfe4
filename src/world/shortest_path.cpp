#include "floornav/world/shortest_path.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include "floornav/geometry/polygon.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

constexpr double kSqrt2 = 1.41421356237309504880;
constexpr double kInf = std::numeric_limits<double>::infinity();

double octile_distance(int dx, int dy) {
  const int ax = std::abs(dx), ay = std::abs(dy);
  const int lo = std::min(ax, ay), hi = std::max(ax, ay);
  return (hi - lo) + kSqrt2 * lo;
}

double polyline_length(std::span<const Vec2> points) {
  double sum = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) sum += (points[i] - points[i - 1]).norm();
  return sum;
}

/// The frame of the raster for `world`, or nullopt when it would be too large.
std::optional<RasterFrame> choose_frame(const World& world, double r, const Vec2& start,
                                        std::span<const Vec2> goals,
                                        const OptimumOptions& options) {
  RasterFrame f;
  if (const OccupancyGrid* g = world.grid()) {
    f.origin = g->origin();
    f.cell = g->resolution();
    f.width = g->width();
    f.height = g->height();
    if (static_cast<double>(f.width) * f.height > static_cast<double>(options.max_cells))
      return std::nullopt;
    return f;
  }
  Box2 box;
  if (world.bounds()) {
    box = *world.bounds();
  } else {
    box.min = box.max = start;
    auto grow = [&](const Vec2& p) {
      box.min = box.min.cwiseMin(p);
      box.max = box.max.cwiseMax(p);
    };
    for (const Vec2& g : goals) grow(g);
    const Box2& e = world.extent();
    if (e.max.x() > e.min.x() || e.max.y() > e.min.y()) {
      grow(e.min);
      grow(e.max);
    }
  }
  double cell = options.cell_finer_than_radius
                    ? std::min(options.cell_size, r > 0.0 ? r / 2.0 : options.cell_size)
                    : options.cell_size;
  // Outside unbounded worlds, a margin so that the path can go round the outermost obstacles.
  auto padded = [&](double c) -> Vec2 {
    const double m = world.bounds() ? 0.0 : r + 4.0 * c;
    return box.size() + Vec2(2.0 * m, 2.0 * m);
  };
  const Vec2 first = padded(cell);
  const double cells = (first.x() / cell + 1.0) * (first.y() / cell + 1.0);
  if (cells > static_cast<double>(options.max_cells)) {
    cell *= std::sqrt(cells / static_cast<double>(options.max_cells)) * 1.01;
    // Cells coarser than the robot's radius cannot resolve the gaps it fits through.
    if (cell > std::max(r, options.cell_size)) return std::nullopt;
  }
  const double m = world.bounds() ? 0.0 : r + 4.0 * cell;
  const Vec2 size = padded(cell);
  f.origin = Pose2{box.min - Vec2(m, m), 0.0};
  f.cell = cell;
  f.width = std::max(1, static_cast<int>(std::ceil(size.x() / cell)));
  f.height = std::max(1, static_cast<int>(std::ceil(size.y() / cell)));
  if (static_cast<double>(f.width) * f.height > static_cast<double>(options.max_cells))
    return std::nullopt;
  return f;
}

// The raster by one `world.clearance` query per cell centre: the definition, and the way for
// the cases the direct one below does not cover (a negative radius). Clearance is 1-Lipschitz: a
// centre with clearance c decides the next cells of its row up to |c - r| away without more
// queries (free ones stay above r, blocked ones at most r). The margin keeps a rounding error from
// flipping a cell that a query would decide otherwise.
void rasterise_by_queries(const World& world, double r, const RasterFrame& f, FreeRaster& raster) {
  raster.width = f.width;
  raster.height = f.height;
  raster.free.assign(static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height), 0);
  constexpr double kMargin = 1e-9;
  const double max_skip = static_cast<double>(f.width);
  for (int iy = 0; iy < f.height; ++iy) {
    const std::size_t row = static_cast<std::size_t>(iy) * static_cast<std::size_t>(f.width);
    for (int ix = 0; ix < f.width;) {
      const double c = world.clearance(f.to_world(Vec2(ix + 0.5, iy + 0.5)));
      const bool is_free = c > r;
      const double reach = is_free ? c - r - kMargin : r - c - kMargin;  // NaN: no skipping
      const double cells = reach > 0.0 ? std::min(reach / f.cell, max_skip) : 0.0;
      // Cells j = 1, 2, ... further on: free ones need j cell < reach, blocked ones j cell <=
      // reach.
      int skip = static_cast<int>(std::floor(cells));
      if (is_free && skip > 0 && skip == cells) --skip;
      const int end = std::min(f.width, ix + 1 + skip);
      if (is_free)
        std::fill(raster.free.begin() + static_cast<std::ptrdiff_t>(row + ix),
                  raster.free.begin() + static_cast<std::ptrdiff_t>(row + end), 1);
      ix = end;
    }
  }
}

/// The world-frame centres of a raster's cells, computed exactly as RasterFrame::to_world does
/// (the same products and sums, the rotation's sine and cosine taken once).
class CellCentres {
 public:
  explicit CellCentres(const RasterFrame& f)
      : f_(f), c_(std::cos(f.origin.theta)), s_(std::sin(f.origin.theta)) {}
  Vec2 operator()(int ix, int iy) const {
    const Vec2 v = Vec2(ix + 0.5, iy + 0.5) * f_.cell;
    return f_.origin.position + Vec2(c_ * v.x() - s_ * v.y(), s_ * v.x() + c_ * v.y());
  }

 private:
  const RasterFrame& f_;
  double c_, s_;
};

/// Cell-frame box [x0, x1] x [y0, y1] (inclusive, clamped to the raster) of the cells whose
/// centres may lie within `reach` metres of the world-frame box [lo, hi]: one cell of margin, far
/// above any rounding of the frame change.
struct CellBox {
  int x0, x1, y0, y1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};
CellBox cells_near(const RasterFrame& f, const Vec2& lo, const Vec2& hi, double reach) {
  Vec2 a = f.to_cells(lo), b = a;
  for (const Vec2& corner : {Vec2(hi.x(), lo.y()), Vec2(lo.x(), hi.y()), hi}) {
    const Vec2 c = f.to_cells(corner);
    a = a.cwiseMin(c);
    b = b.cwiseMax(c);
  }
  const double m = reach / f.cell + 1.0;
  auto lower = [&](double v, int n) {
    return static_cast<int>(std::clamp(std::floor(v - m - 0.5), 0.0, static_cast<double>(n)));
  };
  auto upper = [&](double v, int n) {
    return static_cast<int>(std::clamp(std::ceil(v + m - 0.5), -1.0, static_cast<double>(n - 1)));
  };
  return {lower(a.x(), f.width), upper(b.x(), f.width), lower(a.y(), f.height),
          upper(b.y(), f.height)};
}

// m: a squared distance clear of r by more than this either way decides a centre (far above
// its rounding); only the others ask `distance` itself.
constexpr double kSure = 1e-9;

// The cells the occupancy grid blocks: by the grid's own distance transform (the nearest occupied
// centre) where it is clear by far, by the grid's clearance query elsewhere.
void mark_grid_cells(const OccupancyGrid& g, double r, const RasterFrame& f,
                     const CellCentres& centre, std::uint8_t* free) {
  const std::size_t w = static_cast<std::size_t>(f.width);
  const bool own_cells = g.origin().position == f.origin.position &&
                         g.origin().theta == f.origin.theta && g.resolution() == f.cell &&
                         g.width() == f.width && g.height() == f.height;
  // Far above the rounding of the grid query's frame change (relative 1e-16 of the origin).
  const double margin = 1e-9 + 1e-12 * (f.origin.position.norm() + f.cell * (w + f.height));
  const double res = f.cell;
  for (int iy = 0; iy < f.height; ++iy)
    for (int ix = 0; ix < f.width; ++ix) {
      std::uint8_t& cell = free[static_cast<std::size_t>(iy) * w + static_cast<std::size_t>(ix)];
      if (own_cells) {
        if (g.occupied(ix, iy)) {
          cell = 0;
          continue;
        }
        const std::int32_t q = g.nearest_occupied_index(ix, iy);
        if (q < 0) continue;  // no occupied cell: the grid's clearance is infinite
        const int dx = std::abs(q % f.width - ix), dy = std::abs(q / f.width - iy);
        // The nearest occupied square is at least the nearest occupied centre less half a
        // diagonal away, and at most as far as that centre's own square.
        const double centres = std::sqrt(static_cast<double>(dx * dx + dy * dy));
        const double ex = std::max(dx - 0.5, 0.0), ey = std::max(dy - 0.5, 0.0);
        const double upper = std::sqrt(ex * ex + ey * ey) * res;
        const double lower = (centres - 0.7071067811865476) * res;
        if (lower > r + margin) continue;
        if (upper < r - margin) {
          cell = 0;
          continue;
        }
      }
      if (!(g.clearance(centre(ix, iy)) > r)) cell = 0;
    }
}

// Walls and polygon edges: each marks the cells it comes within r of.
void mark_near_segments(const World& world, double r, const RasterFrame& f,
                        const CellCentres& centre, std::uint8_t* free) {
  const std::size_t w = static_cast<std::size_t>(f.width);
  // Per row, only the columns where the segment comes within r + 1 cell of the row's centres
  // (the part of it within that height, widened by as much): the cell of margin is far above the
  // rounding of the frame change and of the division.
  const double reach_cells = r / f.cell + 1.0;
  const double sure_in = r > kSure ? (r - kSure) * (r - kSure) : -1.0;
  const double sure_out = (r + kSure) * (r + kSure);
  for (const Segment& s : world.segments()) {
    const CellBox b = cells_near(f, s.a.cwiseMin(s.b), s.a.cwiseMax(s.b), r);
    const Vec2 a = f.to_cells(s.a), d = f.to_cells(s.b) - a;
    const Vec2 e = s.b - s.a;  // world frame
    const double len2 = e.squaredNorm(), inv_len2 = len2 > 0.0 ? 1.0 / len2 : 0.0;
    auto blocks = [&](const Vec2& p) {
      const Vec2 q = s.a + std::clamp((p - s.a).dot(e) * inv_len2, 0.0, 1.0) * e;
      const double d2 = (p - q).squaredNorm();
      if (d2 <= sure_in) return true;
      if (d2 > sure_out) return false;
      return distance(s, p) <= r;
    };
    for (int iy = b.y0; iy <= b.y1; ++iy) {
      const double y = iy + 0.5;
      double t0 = 0.0, t1 = 1.0;
      if (d.y() != 0.0) {
        t0 = (y - reach_cells - a.y()) / d.y();
        t1 = (y + reach_cells - a.y()) / d.y();
        if (t0 > t1) std::swap(t0, t1);
        t0 = std::max(t0, 0.0);
        t1 = std::min(t1, 1.0);
        if (t0 > t1) continue;
      }
      const double xa = a.x() + t0 * d.x(), xb = a.x() + t1 * d.x();
      const int x0 = std::max(b.x0, static_cast<int>(std::floor(std::min(xa, xb) - reach_cells)));
      const int x1 = std::min(b.x1, static_cast<int>(std::ceil(std::max(xa, xb) + reach_cells)));
      for (int ix = x0; ix <= x1; ++ix) {
        std::uint8_t& cell = free[static_cast<std::size_t>(iy) * w + static_cast<std::size_t>(ix)];
        if (cell && blocks(centre(ix, iy))) cell = 0;
      }
    }
  }
}

// Circles: the cells inside a disc or within r of it.
void mark_near_circles(const World& world, double r, const RasterFrame& f,
                       const CellCentres& centre, std::uint8_t* free) {
  const std::size_t w = static_cast<std::size_t>(f.width);
  for (const Circle& c : world.circles()) {
    const Vec2 half(c.radius, c.radius);
    const CellBox b = cells_near(f, c.center - half, c.center + half, r);
    const double lo = c.radius + r - kSure, hi = c.radius + r + kSure;
    const double circle_in = lo > 0.0 ? lo * lo : -1.0, circle_out = hi * hi;
    for (int iy = b.y0; iy <= b.y1; ++iy)
      for (int ix = b.x0; ix <= b.x1; ++ix) {
        std::uint8_t& cell = free[static_cast<std::size_t>(iy) * w + static_cast<std::size_t>(ix)];
        if (!cell) continue;
        // Inside the disc or within r of it (its |signed distance| when outside).
        const Vec2 p = centre(ix, iy);
        const double d2 = (p - c.center).squaredNorm();
        if (d2 <= circle_in || (d2 <= circle_out && signed_distance(c, p) <= r)) cell = 0;
      }
  }
}

// Cells still free that may lie inside a polygon. Unrotated, each row of centres is a line
// y = const: the polygon's edges cross it at points in increasing x, and a centre is inside
// when an odd number of crossings lie left of it (the half-open rule counts a vertex on the
// line once). A still free centre is farther than r from every edge, so from every crossing;
// only one within `margin` of a crossing (possible for r ~ 0) asks the world.
void mark_inside_polygons(const World& world, const RasterFrame& f, const CellCentres& centre,
                          std::uint8_t* free) {
  const std::size_t w = static_cast<std::size_t>(f.width);
  auto inside_test = [&](int ix, int iy) {
    std::uint8_t& cell = free[static_cast<std::size_t>(iy) * w + static_cast<std::size_t>(ix)];
    if (cell && world.is_inside_obstacle(centre(ix, iy))) cell = 0;
  };
  std::vector<double> crossings;
  const double margin = 1e-9 + 1e-12 * (f.origin.position.norm() + f.cell * (w + f.height));
  for (const auto& poly : world.polygons()) {
    if (poly.empty()) continue;
    Vec2 lo = poly.front(), hi = poly.front();
    for (const Vec2& v : poly) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
    const CellBox b = cells_near(f, lo, hi, 0.0);
    for (int iy = b.y0; iy <= b.y1; ++iy) {
      if (f.origin.theta != 0.0) {
        for (int ix = b.x0; ix <= b.x1; ++ix) inside_test(ix, iy);
        continue;
      }
      const double y = centre(0, iy).y();
      crossings.clear();
      for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const Vec2 &p = poly[i], &q = poly[j];
        if ((p.y() > y) != (q.y() > y))
          crossings.push_back(p.x() + (y - p.y()) * (q.x() - p.x()) / (q.y() - p.y()));
      }
      std::sort(crossings.begin(), crossings.end());
      std::size_t left = 0;  // crossings left of the centre
      for (int ix = b.x0; ix <= b.x1; ++ix) {
        const double x = centre(ix, iy).x();
        while (left < crossings.size() && crossings[left] < x) ++left;
        const bool near_left = left > 0 && x - crossings[left - 1] <= margin;
        const bool near_right = left < crossings.size() && crossings[left] - x <= margin;
        if (near_left || near_right)
          inside_test(ix, iy);
        else if (left % 2 == 1)
          free[static_cast<std::size_t>(iy) * w + static_cast<std::size_t>(ix)] = 0;
      }
    }
  }
}

// Centres outside the bounds. Unrotated, a centre's x depends on its column only and its y on
// its row only.
void mark_outside_bounds(const Box2& bounds, const RasterFrame& f, const CellCentres& centre,
                         std::uint8_t* free) {
  const std::size_t w = static_cast<std::size_t>(f.width);
  std::vector<std::uint8_t> column_in, row_in;
  if (f.origin.theta == 0.0) {
    column_in.resize(w);
    row_in.resize(static_cast<std::size_t>(f.height));
    for (int ix = 0; ix < f.width; ++ix) {
      const double x = centre(ix, 0).x();
      column_in[static_cast<std::size_t>(ix)] = x >= bounds.min.x() && x <= bounds.max.x();
    }
    for (int iy = 0; iy < f.height; ++iy) {
      const double y = centre(0, iy).y();
      row_in[static_cast<std::size_t>(iy)] = y >= bounds.min.y() && y <= bounds.max.y();
    }
  }
  for (int iy = 0; iy < f.height; ++iy) {
    std::uint8_t* row = free + static_cast<std::size_t>(iy) * w;
    if (!row_in.empty()) {
      if (!row_in[static_cast<std::size_t>(iy)]) std::fill(row, row + w, 0);
      for (std::size_t ix = 0; ix < w; ++ix) row[ix] &= column_in[ix];
      continue;
    }
    for (int ix = 0; ix < f.width; ++ix)
      if (row[ix] && !bounds.contains(centre(ix, iy))) row[ix] = 0;
  }
}

// A map without bounds: off the map is solid as outside the bounds is (World::clearance).
void mark_off_map(std::span<const Vec2> edge, const RasterFrame& f, const CellCentres& centre,
                  std::uint8_t* free) {
  const std::size_t w = static_cast<std::size_t>(f.width);
  for (int iy = 0; iy < f.height; ++iy)
    for (int ix = 0; ix < f.width; ++ix) {
      std::uint8_t& cell = free[static_cast<std::size_t>(iy) * w + static_cast<std::size_t>(ix)];
      if (cell && !contains(edge, centre(ix, iy))) cell = 0;
    }
}

// The raster a clearance query per cell centre gives (rasterise_by_queries), computed from the
// obstacles instead: each cell is as free as that query says, no more, no less (tested on random
// worlds). A centre is blocked when the world's clearance there is at most r, that is when
//  - the occupancy grid's clearance is at most r: decided by the grid's own distance transform
//    (the nearest occupied centre) where it is clear by far, by the grid's query elsewhere;
//  - or a wall, polygon edge or circle lies within r: World::clearance takes the minimum of the
//    same `distance` / `signed_distance` values over them, so each is computed for the cells near
//    it only and compared with r;
//  - or the centre lies inside a solid shape or outside the bounds: World::is_inside_obstacle,
//    asked only for the still free cells that may be.
// Into `raster`, whose memory is reused (a batch builds one per world).
void rasterise(const World& world, double r, const RasterFrame& f, FreeRaster& raster) {
  if (!(r >= 0.0) || !is_finite(f.origin.position) || !std::isfinite(f.origin.theta)) {
    rasterise_by_queries(world, r, f, raster);
    return;
  }
  raster.width = f.width;
  raster.height = f.height;
  const std::size_t w = static_cast<std::size_t>(f.width);
  raster.free.assign(w * static_cast<std::size_t>(f.height), 1);
  std::uint8_t* free = raster.free.data();
  const CellCentres centre(f);

  if (const OccupancyGrid* g = world.grid()) mark_grid_cells(*g, r, f, centre, free);
  mark_near_segments(world, r, f, centre, free);
  mark_near_circles(world, r, f, centre, free);
  mark_inside_polygons(world, f, centre, free);
  if (const auto& bounds = world.bounds()) mark_outside_bounds(*bounds, f, centre, free);
  if (const std::span<const Vec2> edge = world.map_edge(); !edge.empty())
    mark_off_map(edge, f, centre, free);
}

}  // namespace

std::optional<GridCell> snap_to_free(const FreeRaster& raster, const Vec2& p, double radius) {
  const int cx = static_cast<int>(std::floor(std::clamp(p.x(), -1e9, 1e9)));
  const int cy = static_cast<int>(std::floor(std::clamp(p.y(), -1e9, 1e9)));
  if (raster.is_free(cx, cy)) return GridCell{cx, cy};
  const int reach = static_cast<int>(std::ceil(radius));
  std::optional<GridCell> best;
  double best_d = kInf;
  for (int y = std::max(0, cy - reach); y <= std::min(raster.height - 1, cy + reach); ++y)
    for (int x = std::max(0, cx - reach); x <= std::min(raster.width - 1, cx + reach); ++x) {
      if (!raster.is_free(x, y)) continue;
      const double d = (Vec2(x + 0.5, y + 0.5) - p).norm();
      if (d <= radius + 0.5 && d < best_d) best_d = d, best = GridCell{x, y};
    }
  return best;
}

FreeRaster free_cells(const World& world, double body_radius, const RasterFrame& frame) {
  if (frame.width <= 0 || frame.height <= 0 || !(frame.cell > 0.0)) return {};
  FreeRaster raster;
  rasterise(world, body_radius, frame, raster);
  return raster;
}

std::optional<RasterFrame> choose_raster_frame(const World& world, double body_radius,
                                               const Vec2& start, std::span<const Vec2> goals,
                                               const OptimumOptions& options) {
  if (!is_finite(start) || !std::isfinite(body_radius) || body_radius < 0.0 ||
      !(options.cell_size > 0.0))
    return std::nullopt;
  return choose_frame(world, body_radius, start, goals, options);
}

FreeRaster free_cells(const World& world, double body_radius, const Pose2& origin, double cell,
                      int width, int height) {
  if (width <= 0 || height <= 0 || !(cell > 0.0)) return {};
  FreeRaster raster;
  rasterise(world, body_radius, RasterFrame{origin, cell, width, height}, raster);
  return raster;
}

namespace {

/// An open-list entry: lowest f first; among equal f the deepest node (-g lowest), then the
/// lowest index, so that the order of expansion (and the path) is deterministic.
struct OpenEntry {
  double f;
  double neg_g;
  std::uint32_t index;
  bool operator>(const OpenEntry& o) const {
    if (f != o.f) return f > o.f;
    if (neg_g != o.neg_g) return neg_g > o.neg_g;
    return index > o.index;
  }
};

/// The open list, a radix heap on f: A* with a consistent heuristic pops f in increasing order, so
/// an entry whose f differs from the last popped one first in bit b (of f's IEEE pattern, which
/// orders non-negative doubles as unsigned integers do) waits in bucket b + 1, unsorted, until
/// everything below it is gone. Bucket 0 holds the entries with f at most the last popped one,
/// sorted on (f, -g, index), the best last: pops come out in the order of one priority queue over
/// all entries (the order is total, so the path is that of any exact priority queue).
/// Bucket 0 is a sorted vector, not a heap, because of where its pushes land: an entry pushed while
/// cell u is expanded has f at most u's (else it goes to a higher bucket) and, at equal f, a
/// larger g (u's g plus a step), so it is better than u, which was the best of all: it goes on top,
/// or below the few entries pushed just before it from the same u. Only the odd entry a rounding
/// puts an ulp off scans further down. Pushes and pops are therefore O(1) where a binary heap of
/// the hundreds of entries that tie on f would sift through its levels, with the same paths
/// (BM_FloorOptimumAstar in bench/optimum_bench.cpp decides this).
class OpenList {
 public:
  void clear() {
    for (auto& b : buckets_) b.clear();
    last_ = 0;
    size_ = 0;
  }
  bool empty() const { return size_ == 0; }
  void push(const OpenEntry& e) {
    ++size_;
    const std::uint64_t key = bits(e.f);
    if (key <= last_) {
      push_ordered(e);
      return;
    }
    buckets_[bucket_of(key)].push_back(e);
  }
  OpenEntry pop() {
    --size_;
    auto& zero = buckets_[0];
    if (zero.empty()) {
      std::size_t b = 1;
      while (buckets_[b].empty()) ++b;
      auto& from = buckets_[b];
      std::uint64_t least = bits(from.front().f);
      for (const OpenEntry& e : from) least = std::min(least, bits(e.f));
      last_ = least;
      for (const OpenEntry& e : from) {
        const std::uint64_t key = bits(e.f);
        if (key == least)
          zero.push_back(e);
        else
          buckets_[bucket_of(key)].push_back(e);  // a lower bucket: they share the top bits
      }
      from.clear();
      std::sort(zero.begin(), zero.end(), std::greater<OpenEntry>{});  // the best last
    }
    const OpenEntry top = zero.back();
    zero.pop_back();
    return top;
  }

 private:
  static std::uint64_t bits(double f) { return std::bit_cast<std::uint64_t>(f); }
  std::size_t bucket_of(std::uint64_t key) const {
    return static_cast<std::size_t>(64 - std::countl_zero(key ^ last_));
  }
  void push_ordered(const OpenEntry& e) {
    // Insertion from the top: e is nearly always the best already.
    auto& zero = buckets_[0];
    std::size_t i = zero.size();
    zero.push_back(e);
    for (; i > 0 && e > zero[i - 1]; --i) zero[i] = zero[i - 1];
    zero[i] = e;
  }

  std::array<std::vector<OpenEntry>, 65> buckets_;
  std::uint64_t last_{0};
  std::size_t size_{0};
};

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
      cells.assign(std::max(n, cells.size()), CellState{kInf, -1, 0});
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

/// Octile A*'s successors: the eight neighbours, each reached through a free cell, diagonals not
/// cutting a corner.
class OctileNeighbours {
 public:
  explicit OctileNeighbours(const FreeRaster& raster)
      : raster_(raster), free_(raster.free.data()), width_(raster.width), height_(raster.height) {
    const std::ptrdiff_t sw = raster.width;
    step_ = {1, -1, sw, -sw, sw + 1, -sw + 1, sw - 1, -sw - 1};
  }

  template <class Relax>
  __attribute__((always_inline)) void operator()(std::size_t u, int ux, int uy, std::int32_t,
                                                 Relax& relax) const {
    // Neighbour u + step_[k] (k < 4 straight, else diagonal) of length kLength[k] (a load, not a
    // branch on the direction); the order of the relaxations does not matter (each pair once).
    // Tables in the function, not static members: indexing those takes two of the search loop's
    // registers (BM_FloorOptimumAstar's instructions under callgrind decide this).
    constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
    constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    constexpr double kLength[8] = {1.0, 1.0, 1.0, 1.0, kSqrt2, kSqrt2, kSqrt2, kSqrt2};
    auto move = [&](int k) __attribute__((always_inline)) {
      relax(u + static_cast<std::size_t>(step_[static_cast<std::size_t>(k)]), kDx[k], kDy[k],
            [&] { return kLength[k]; });
    };
    if (ux > 0 && uy > 0 && ux + 1 < width_ && uy + 1 < height_) {
      // Away from the raster's border every neighbour exists: the moves as a bit mask of the
      // 3 x 3 block, without bounds checks or a branch per neighbour.
      const std::ptrdiff_t sw = width_;
      const std::uint8_t* c = free_ + u;
      const unsigned e = c[1] != 0, west = c[-1] != 0, n = c[sw] != 0, south = c[-sw] != 0;
      unsigned moves = e | west << 1 | n << 2 | south << 3 | (e & n & (c[sw + 1] != 0)) << 4 |
                       (e & south & (c[-sw + 1] != 0)) << 5 | (west & n & (c[sw - 1] != 0)) << 6 |
                       (west & south & (c[-sw - 1] != 0)) << 7;
      for (; moves != 0; moves &= moves - 1) move(std::countr_zero(moves));
      return;
    }
    for (int k = 0; k < 8; ++k) {
      if (!raster_.is_free(ux + kDx[k], uy + kDy[k])) continue;
      if (k >= 4 && (!raster_.is_free(ux + kDx[k], uy) || !raster_.is_free(ux, uy + kDy[k])))
        continue;  // no corner cutting
      move(k);
    }
  }

 private:
  const FreeRaster& raster_;
  // Copies, so that the search's stores cannot be taken to change them.
  const std::uint8_t* free_;
  int width_, height_;
  std::array<std::ptrdiff_t, 8> step_;
};

/// Octile A* (run_octile_search over every neighbour).
bool run_octile_astar(SearchBuffers& b, const FreeRaster& raster, GridCell start, GridCell goal,
                      GridPath& path, std::size_t& expanded) {
  return run_octile_search(b, raster, start, goal, OctileNeighbours(raster), path, expanded);
}

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

std::optional<GridPath> octile_astar(const FreeRaster& raster, GridCell start, GridCell goal) {
  thread_local SearchBuffers buffers;  // a batch's thousands of searches allocate nothing
  GridPath path;
  std::size_t expanded = 0;
  if (!run_octile_astar(buffers, raster, start, goal, path, expanded)) return std::nullopt;
  return path;
}

std::optional<GridPath> octile_jump_point_search(const FreeRaster& raster, GridCell start,
                                                 GridCell goal) {
  thread_local SearchBuffers buffers;
  GridPath path;
  std::size_t expanded = 0;
  if (!run_octile_jps(buffers, raster, start, goal, path, expanded)) return std::nullopt;
  return path;
}

struct GridSearch::Buffers : SearchBuffers {};

GridSearch::GridSearch() : buffers_(std::make_unique<Buffers>()) {}
GridSearch::~GridSearch() = default;
GridSearch::GridSearch(GridSearch&&) noexcept = default;
GridSearch& GridSearch::operator=(GridSearch&&) noexcept = default;

bool GridSearch::search(const FreeRaster& raster, GridCell start, GridCell goal, GridPath& path) {
  return run_octile_astar(*buffers_, raster, start, goal, path, expanded_);
}

bool line_of_sight(const FreeRaster& raster, const Vec2& a, const Vec2& b) {
  if (!is_finite(a) || !is_finite(b)) return false;
  constexpr double kEps = 1e-9;  // a touch of a border or corner counts (conservative)
  const Vec2 lo = a.x() <= b.x() ? a : b;
  const Vec2 hi = a.x() <= b.x() ? b : a;
  const double dx = hi.x() - lo.x();
  const int x0 = static_cast<int>(std::floor(lo.x() - kEps));
  const int x1 = static_cast<int>(std::floor(hi.x() + kEps));
  const double slope = dx > 0.0 ? (hi.y() - lo.y()) / dx : 0.0;
  // Inside the raster (the segment's columns, and its rows widened by a whole cell, far above
  // any rounding of the rows below), the cells are read without bounds checks: the same cells.
  const bool inside = x0 >= 0 && x1 < raster.width && std::min(lo.y(), hi.y()) >= 1.0 &&
                      std::max(lo.y(), hi.y()) + 1.0 < raster.height;
  const std::size_t w = static_cast<std::size_t>(std::max(raster.width, 0));
  for (int ix = x0; ix <= x1; ++ix) {
    // The part of the segment within column ix (widened by kEps), then the rows it spans.
    const double xa = std::max(lo.x(), ix - kEps), xb = std::min(hi.x(), ix + 1 + kEps);
    double ya = lo.y(), yb = hi.y();
    if (dx > 0.0) {
      ya = lo.y() + slope * (xa - lo.x());
      yb = lo.y() + slope * (xb - lo.x());
    }
    if (ya > yb) std::swap(ya, yb);
    const int y0 = static_cast<int>(std::floor(ya - kEps));
    const int y1 = static_cast<int>(std::floor(yb + kEps));
    if (inside) {
      const std::uint8_t* c = raster.free.data() + static_cast<std::size_t>(ix);
      for (int iy = y0; iy <= y1; ++iy)
        if (!c[static_cast<std::size_t>(iy) * w]) return false;
      continue;
    }
    for (int iy = y0; iy <= y1; ++iy)
      if (!raster.is_free(ix, iy)) return false;
  }
  return true;
}

std::vector<Vec2> pull_string(const FreeRaster& raster, std::span<const Vec2> points) {
  std::vector<Vec2> out;
  if (points.empty()) return out;
  out.push_back(points[0]);
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
    if (!line_of_sight(raster, out.back(), points[i + 1])) out.push_back(points[i]);
  if (points.size() > 1) out.push_back(points.back());
  return out;
}

namespace {

bool valid_route(const Vec2& start, std::span<const Vec2> goals) {
  return !goals.empty() && is_finite(start) &&
         std::all_of(goals.begin(), goals.end(), [](const Vec2& g) { return is_finite(g); });
}

bool valid_radius(double body_radius, const OptimumOptions& options) {
  return std::isfinite(body_radius) && body_radius >= 0.0 && options.cell_size > 0.0;
}

void make_raster(const World& world, double body_radius, const std::optional<RasterFrame>& frame,
                 OptimumRaster& r) {
  if (!frame) {
    r.status = OptimumStatus::RasterTooLarge;
    return;
  }
  r.status = OptimumStatus::Found;
  r.origin = frame->origin;
  r.cell = frame->cell;
  rasterise(world, body_radius, *frame, r.raster);
}

}  // namespace

bool build_optimum_raster(const World& world, double body_radius, const OptimumOptions& options,
                          OptimumRaster& out) {
  // Without bounds or a grid, the raster spans the route too.
  if (!world.bounds() && !world.grid()) return false;
  if (!valid_radius(body_radius, options)) {
    out.status = OptimumStatus::InvalidInput;
    return true;
  }
  const Vec2 any = Vec2::Zero();  // the frame of a bounded or gridded world ignores the route
  make_raster(world, body_radius,
              choose_frame(world, body_radius, any, std::span<const Vec2>(&any, 1), options), out);
  return true;
}

Optimum scenario_optimum(const World& world, double body_radius, const Vec2& start,
                         std::span<const Vec2> goals, const OptimumOptions& options) {
  if (!valid_route(start, goals) || !valid_radius(body_radius, options)) return {};
  thread_local OptimumRaster raster;  // its memory serves every call on this thread
  make_raster(world, body_radius, choose_frame(world, body_radius, start, goals, options), raster);
  return scenario_optimum(raster, start, goals, options);
}

Optimum scenario_optimum(const OptimumRaster& grid, const Vec2& start, std::span<const Vec2> goals,
                         const OptimumOptions& options) {
  Optimum out;
  if (!valid_route(start, goals) || !(options.cell_size > 0.0)) return out;
  if (grid.status != OptimumStatus::Found) {
    out.status = grid.status;
    return out;
  }
  const RasterFrame frame{grid.origin, grid.cell, grid.raster.width, grid.raster.height};
  const FreeRaster& raster = grid.raster;
  out.cell_size = frame.cell;
  out.width = frame.width;
  out.height = frame.height;

  double length = 0.0, octile = 0.0;
  std::vector<Vec2> route;
  Vec2 from = frame.to_cells(start);
  auto from_cell = snap_to_free(raster, from, options.snap_radius);
  for (const Vec2& goal_world : goals) {
    const Vec2 to = frame.to_cells(goal_world);
    const auto to_cell = snap_to_free(raster, to, options.snap_radius);
    if (!from_cell || !to_cell) {
      out.status = OptimumStatus::NoFreeCell;
      return out;
    }
    const auto path = octile_jump_point_search(raster, *from_cell, *to_cell);
    if (!path) {
      out.status = OptimumStatus::Unreachable;
      return out;
    }
    // The polyline: exact start, the cell centres, exact goal (cell units).
    std::vector<Vec2> points;
    points.reserve(path->cells.size() + 2);
    points.push_back(from);
    for (const GridCell& c : path->cells) points.emplace_back(c.x + 0.5, c.y + 0.5);
    points.push_back(to);
    const double leg_octile = polyline_length(points);
    octile += leg_octile;
    if (options.smooth) points = pull_string(raster, points);
    length += options.smooth ? polyline_length(points) : leg_octile;
    for (std::size_t i = route.empty() ? 0 : 1; i < points.size(); ++i)
      route.push_back(frame.to_world(points[i]));
    from = to;
    from_cell = to_cell;
  }
  out.status = OptimumStatus::Found;
  out.length = length * frame.cell;
  out.octile_length = octile * frame.cell;
  out.path = std::move(route);
  return out;
}

}  // namespace floornav
