#include "floornav/planning/free_cells.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/geometry/segment.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

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

}  // namespace

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
void free_cells_into(const World& world, double r, const RasterFrame& f, FreeRaster& raster) {
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

FreeRaster free_cells(const World& world, double body_radius, const RasterFrame& frame) {
  if (frame.width <= 0 || frame.height <= 0 || !(frame.cell > 0.0)) return {};
  FreeRaster raster;
  free_cells_into(world, body_radius, frame, raster);
  return raster;
}

FreeRaster free_cells(const World& world, double body_radius, const Pose2& origin, double cell,
                      int width, int height) {
  if (width <= 0 || height <= 0 || !(cell > 0.0)) return {};
  FreeRaster raster;
  free_cells_into(world, body_radius, RasterFrame{origin, cell, width, height}, raster);
  return raster;
}

}  // namespace floornav
