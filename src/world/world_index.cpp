#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>

#include "cell_index.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/geometry/ray.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

// World's spatial index: a uniform grid of cells listing the obstacles that cross each, built
// once; the ray casts and clearance queries that walk it.

namespace floornav {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
using cell_detail::clamp_cell;
}  // namespace

void World::build_index() {
  Index& ix = index_;
  const std::size_t items = segments_.size() + circles_.size();
  const Vec2 size = extent_.size();
  const double area = std::max(size.x(), 1e-3) * std::max(size.y(), 1e-3);
  // About two items per cell on average, but never more than ~1M cells nor cells under 5 cm.
  double cell = std::sqrt(area / std::max<double>(1.0, 0.5 * static_cast<double>(items)));
  cell = std::max(cell, std::sqrt(area / 1.0e6));
  cell = std::max(cell, 0.05);
  // Large obstacles are registered in every cell their box covers, so many big overlapping ones
  // could need far more entries than cells. Coarsen the grid until the entries fit a budget, so
  // that no input can make building the index take unbounded time or memory.
  constexpr double kMaxEntries = 2.0e7;
  auto entries = [&](double c) {
    auto span = [c](double lo, double hi) { return std::floor(hi / c) - std::floor(lo / c) + 2.0; };
    double total = 0.0;
    for (const Segment& sg : segments_)
      total += span(std::min(sg.a.x(), sg.b.x()), std::max(sg.a.x(), sg.b.x())) *
               span(std::min(sg.a.y(), sg.b.y()), std::max(sg.a.y(), sg.b.y()));
    for (const Circle& ci : circles_)
      total += span(ci.center.x() - ci.radius, ci.center.x() + ci.radius) *
               span(ci.center.y() - ci.radius, ci.center.y() + ci.radius);
    for (const Box2& b : polygon_boxes_)
      total += span(b.min.x(), b.max.x()) * span(b.min.y(), b.max.y());
    return total;
  };
  while (entries(cell) > kMaxEntries && cell < 1e12) cell *= 2.0;
  ix.cell = cell;
  ix.inv_cell = 1.0 / cell;
  ix.origin = extent_.min - Vec2(1e-9, 1e-9);
  ix.nx = std::max(1, static_cast<int>(std::ceil((size.x() + 2e-9) / cell)));
  ix.ny = std::max(1, static_cast<int>(std::ceil((size.y() + 2e-9) / cell)));
  const std::size_t ncell = static_cast<std::size_t>(ix.nx) * static_cast<std::size_t>(ix.ny);

  // Two passes per list (count, then fill) keep the storage compressed and contiguous.
  auto fill = [&](std::size_t count, auto&& cells_of, std::vector<std::uint32_t>& offsets,
                  std::vector<std::uint32_t>& out) {
    std::vector<std::uint32_t> counts(ncell + 1, 0);
    for (std::size_t i = 0; i < count; ++i) cells_of(i, [&](std::size_t c) { ++counts[c + 1]; });
    for (std::size_t c = 0; c < ncell; ++c) counts[c + 1] += counts[c];
    offsets = counts;
    out.assign(counts[ncell], 0);
    for (std::size_t i = 0; i < count; ++i)
      cells_of(i, [&](std::size_t c) { out[counts[c]++] = static_cast<std::uint32_t>(i); });
  };
  auto box_cells = [&](const Vec2& lo, const Vec2& hi, auto&& keep, auto&& emit) {
    const int x0 = cell_x(lo.x()), x1 = cell_x(hi.x());
    const int y0 = cell_y(lo.y()), y1 = cell_y(hi.y());
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        if (keep(x, y)) emit(static_cast<std::size_t>(y) * ix.nx + x);
  };
  const double half_diag = 0.5 * std::sqrt(2.0) * cell;
  fill(
      segments_.size(),
      [&](std::size_t i, auto&& emit) {
        const Segment& s = segments_[i];
        box_cells(
            s.a.cwiseMin(s.b), s.a.cwiseMax(s.b),
            [&](int x, int y) {
              const Vec2 centre = ix.origin + Vec2((x + 0.5) * cell, (y + 0.5) * cell);
              return distance(s, centre) <= half_diag + 1e-9;
            },
            emit);
      },
      ix.segment_offsets, ix.segment_items);
  ix.segment_rays.reserve(ix.segment_items.size());
  ix.segment_sides.reserve(ix.segment_items.size());
  for (const std::uint32_t i : ix.segment_items) {
    ix.segment_rays.push_back({segments_[i].a, segments_[i].b - segments_[i].a,
                               segments_[i].a.cwiseMin(segments_[i].b),
                               segments_[i].a.cwiseMax(segments_[i].b)});
    ix.segment_sides.push_back(solid_sides_[i]);
  }
  fill(
      circles_.size(),
      [&](std::size_t i, auto&& emit) {
        const Circle& c = circles_[i];
        const Vec2 r(c.radius, c.radius);
        box_cells(
            c.center - r, c.center + r, [](int, int) { return true; }, emit);
      },
      ix.circle_offsets, ix.circle_items);
  fill(
      polygons_.size(),
      [&](std::size_t i, auto&& emit) {
        box_cells(
            polygon_boxes_[i].min, polygon_boxes_[i].max, [](int, int) { return true; }, emit);
      },
      ix.polygon_offsets, ix.polygon_items);
}

int World::cell_x(double x) const {
  return clamp_cell((x - index_.origin.x()) * index_.inv_cell, index_.nx);
}

int World::cell_y(double y) const {
  return clamp_cell((y - index_.origin.y()) * index_.inv_cell, index_.ny);
}

double World::ray_in_cell(int cell, const Vec2& origin, const Vec2& dir, double best,
                          const Box2* ray_box) const {
  const auto c = static_cast<std::size_t>(cell);
  const SegmentRay* rays = index_.segment_rays.data();
  const double* sides = index_.segment_sides.data();
  const auto segments = [&](auto boxed) {
    for (std::uint32_t k = index_.segment_offsets[c]; k < index_.segment_offsets[c + 1]; ++k) {
      const SegmentRay& s = rays[k];
      // A segment whose box misses the (short) ray's box cannot be hit: skip the test.
      if constexpr (decltype(boxed)::value) {
        if (s.lo.x() > ray_box->max.x() || s.hi.x() < ray_box->min.x() ||
            s.lo.y() > ray_box->max.y() || s.hi.y() < ray_box->min.y())
          continue;
      }
      if (seen_from_solid_side(sides[k], s.a - origin, s.e)) continue;
      best = ray_segment_hit(origin, dir, s.a, segments_[index_.segment_items[k]].b, s.e, best);
    }
  };
  if (ray_box != nullptr)
    segments(std::true_type{});
  else
    segments(std::false_type{});
  for (std::uint32_t k = index_.circle_offsets[c]; k < index_.circle_offsets[c + 1]; ++k)
    best = ray_circle_hit(origin, dir, circles_[index_.circle_items[k]], best);
  return best;
}

double World::cast_ray(const Vec2& origin, const Vec2& dir, double max_range) const {
  if (inside_solid_shape(origin)) return 0.0;
  return cast_ray_from_free(origin, dir, max_range);
}

double World::cast_ray_from_free(const Vec2& origin, const Vec2& dir, double max_range) const {
  double best = max_range;
  if (grid_) best = std::min(best, grid_->cast_ray(origin, dir, max_range));
  if (segments_.empty() && circles_.empty()) return best;

  const Index& ix = index_;
  const Vec2 lo = ix.origin;
  const Vec2 hi = ix.origin + Vec2(ix.nx * ix.cell, ix.ny * ix.cell);

  // A short ray (an IR sensor's) usually stays in one cell. Then every surface it can hit before
  // `best` passes through that cell, so it is among the cell's items: the cell alone gives the
  // walk's answer, bit for bit. The margin keeps the box test clear of rounding.
  // (A ray longer than a cell's diagonal cannot fit in one.)
  if (best <= 1.5 * ix.cell) {
    constexpr double kMargin = 1e-9;  // m
    const Vec2 end = origin + best * dir;
    const Box2 ray_box{origin.cwiseMin(end).array() - kMargin,
                       origin.cwiseMax(end).array() + kMargin};
    if (ray_box.min.x() >= lo.x() && ray_box.min.y() >= lo.y() && ray_box.max.x() <= hi.x() &&
        ray_box.max.y() <= hi.y()) {
      const int x = cell_x(ray_box.min.x()), y = cell_y(ray_box.min.y());
      if (x == cell_x(ray_box.max.x()) && y == cell_y(ray_box.max.y()))
        return ray_in_cell(y * ix.nx + x, origin, dir, best, &ray_box);
    }
  }

  // Clip the ray to the index box, then walk its cells in order (Amanatides & Woo). A hit found
  // in a cell is final once it lies before the cell's exit. A ray starting inside the box needs
  // no clipping: it enters at t = 0, and the walk stops where it leaves the box.
  double t_enter = 0.0, t_exit = best;
  const bool starts_inside =
      origin.x() > lo.x() && origin.x() < hi.x() && origin.y() > lo.y() && origin.y() < hi.y();
  if (!starts_inside && !clip_ray_to_box(origin, dir, Box2{lo, hi}, t_enter, t_exit)) return best;
  const Vec2 start = origin + t_enter * dir;
  int x = cell_x(start.x()), y = cell_y(start.y());
  const int step_x = dir.x() > 0 ? 1 : -1;
  const int step_y = dir.y() > 0 ? 1 : -1;
  const double dtx = std::abs(dir.x()) > 1e-300 ? ix.cell / std::abs(dir.x()) : kInf;
  const double dty = std::abs(dir.y()) > 1e-300 ? ix.cell / std::abs(dir.y()) : kInf;
  const double next_x_edge = lo.x() + (x + (step_x > 0 ? 1 : 0)) * ix.cell;
  const double next_y_edge = lo.y() + (y + (step_y > 0 ? 1 : 0)) * ix.cell;
  double tx = dtx < kInf ? (next_x_edge - origin.x()) / dir.x() : kInf;
  double ty = dty < kInf ? (next_y_edge - origin.y()) / dir.y() : kInf;
  while (true) {
    best = ray_in_cell(y * ix.nx + x, origin, dir, best);
    const double t_cell_exit = std::min(tx, ty);
    if (best <= t_cell_exit || t_cell_exit >= t_exit) break;
    if (tx < ty) {
      x += step_x;
      tx += dtx;
      if (x < 0 || x >= ix.nx) break;
    } else {
      y += step_y;
      ty += dty;
      if (y < 0 || y >= ix.ny) break;
    }
  }
  return best;
}

namespace {

// The three nearest distinct items offered (an item is listed in every cell it crosses, and
// offered again with the same distance).
struct NearestThree {
  std::array<double, 3> d{kInf, kInf, kInf};
  std::array<std::uint32_t, 3> id{ClearanceHint::kNone, ClearanceHint::kNone, ClearanceHint::kNone};
  void offer(double v, std::uint32_t item) {
    if (!(v < d[2]) || item == id[0] || item == id[1] || item == id[2]) return;
    int k = 2;
    for (; k > 0 && v < d[k - 1]; --k) {
      d[k] = d[k - 1];
      id[k] = id[k - 1];
    }
    d[k] = v;
    id[k] = item;
  }
};

}  // namespace

template <bool kHint>
double World::shape_clearance(const Vec2& p, ClearanceHint* hint) const {
  const Index& ix = index_;
  // Search rings of cells around p's cell; items in ring k are at least (k - 1) cells away
  // from p, so stop once that bound exceeds the best distance found.
  const int cx = cell_x(p.x()), cy = cell_y(p.y());
  // Distance from p to the index box (p may lie outside it).
  const Vec2 lo = ix.origin, hi = ix.origin + Vec2(ix.nx * ix.cell, ix.ny * ix.cell);
  const double outside = (p.cwiseMax(lo).cwiseMin(hi) - p).norm();
  // Segments by squared distance (one square root at the end, the same bits: the root is
  // correctly rounded and monotonic), circles by distance; with a hint, the three nearest of
  // each kind.
  double best_segment2 = kInf, best_circle = kInf;
  NearestThree segments2, circles;
  double unsearched = kInf;  // lower bound on the distance of the items not looked at
  const auto unsigned_best = [&] { return std::min(std::sqrt(best_segment2), best_circle); };
  const int max_ring = std::max(ix.nx, ix.ny);
  for (int k = 0; k <= max_ring; ++k) {
    const double ring_lower_bound = outside + (k - 1) * ix.cell;
    if (ring_lower_bound > unsigned_best()) {
      unsearched = ring_lower_bound;
      break;
    }
    for (int y = cy - k; y <= cy + k; ++y) {
      if (y < 0 || y >= ix.ny) continue;
      const bool edge_row = (y == cy - k || y == cy + k);
      for (int x = cx - k; x <= cx + k; x += (edge_row ? 1 : 2 * k)) {
        if (x >= 0 && x < ix.nx) {
          const auto c = static_cast<std::size_t>(y) * ix.nx + x;
          for (auto j = ix.segment_offsets[c]; j < ix.segment_offsets[c + 1]; ++j) {
            const std::uint32_t item = ix.segment_items[j];
            const double d2 = squared_distance(segments_[item], p);
            best_segment2 = std::min(best_segment2, d2);
            if constexpr (kHint) segments2.offer(d2, item);
          }
          for (auto j = ix.circle_offsets[c]; j < ix.circle_offsets[c + 1]; ++j) {
            const std::uint32_t item = ix.circle_items[j];
            const double d = std::abs(signed_distance(circles_[item], p));
            best_circle = std::min(best_circle, d);
            if constexpr (kHint) circles.offer(d, item);
          }
        }
        if (k == 0) break;
      }
    }
  }
  const double found = unsigned_best();
  const bool inside = inside_solid_shape(p);
  if constexpr (kHint) {
    // The two nearest of both kinds; the third nearest bounds all the others. (A tie with the
    // third leaves no margin: the hint then never answers alone.)
    NearestThree all;
    const auto segment_count = static_cast<std::uint32_t>(segments_.size());
    for (int k = 0; k < 3; ++k) {
      all.offer(std::sqrt(segments2.d[k]), segments2.id[k]);
      if (circles.id[k] != ClearanceHint::kNone)
        all.offer(circles.d[k], circles.id[k] + segment_count);
    }
    hint->at = p;
    hint->nearest = {all.id[0], all.id[1]};
    hint->runner_up = std::min(unsearched, all.d[2]);
    hint->valid = !inside && found > 0.0 && found < kInf;
  }
  return inside ? -found : found;
}

double World::clearance(const Vec2& p) const {
  double best = grid_ ? grid_->clearance(p) : kInf;
  if (!segments_.empty() || !circles_.empty())
    best = std::min(best, shape_clearance<false>(p, nullptr));
  return best;
}

double World::clearance(const Vec2& p, ClearanceHint& hint) const {
  if (grid_ || (segments_.empty() && circles_.empty())) {
    hint.valid = false;
    return clearance(p);
  }
  if (hint.valid) {
    // Far above the rounding of a distance (~1e-15 m), far below any clearance that matters.
    constexpr double kMargin = 1e-9;  // m
    const double moved = (p - hint.at).norm();
    double segment2 = kInf, circle = kInf;
    for (const std::uint32_t k : hint.nearest) {
      if (k == ClearanceHint::kNone) continue;
      if (k < segments_.size())
        segment2 = std::min(segment2, squared_distance(segments_[k], p));
      else
        circle = std::min(circle, std::abs(signed_distance(circles_[k - segments_.size()], p)));
    }
    const double d = std::min(std::sqrt(segment2), circle);
    // Every other item is at least runner_up - moved from p, so `d` is the least distance. And
    // p is outside every shape, as `at` was: a boundary crossed on the way from `at` would lie
    // within `moved` of p.
    if (d > moved + kMargin && d < hint.runner_up - moved - kMargin) return d;
  }
  return shape_clearance<true>(p, &hint);
}

namespace {
// Distance between segment s and the solid polygon; 0 when they meet.
double segment_polygon_distance(const Segment& s, std::span<const Vec2> poly) {
  if (contains(poly, s.a) || contains(poly, s.b)) return 0.0;
  double d = kInf;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Segment e = edge(poly, i);
    if (segments_intersect(s, e)) return 0.0;
    d = std::min({d, distance(e, s.a), distance(e, s.b), distance(s, e.a)});
  }
  return d;
}

}  // namespace

double World::polygon_clearance(std::span<const Vec2> poly, double reach) const {
  const Box2 box = box_of(poly);
  const Vec2 centre = 0.5 * (box.min + box.max);
  double radius = 0.0;  // of the circumscribed disc about the box centre
  for (const Vec2& v : poly) radius = std::max(radius, (v - centre).norm());
  double best = kInf;
  if (grid_) best = grid_->clearance(centre) - radius;
  for (const Vec2& v : poly)
    if (inside_solid_shape(v)) return std::min(best, 0.0);
  const Index& ix = index_;
  const int x0 = cell_x(box.min.x() - reach), x1 = cell_x(box.max.x() + reach);
  const int y0 = cell_y(box.min.y() - reach), y1 = cell_y(box.max.y() + reach);
  double found = kInf;
  if (!segments_.empty() || !circles_.empty()) {
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const auto c = static_cast<std::size_t>(y) * ix.nx + x;
        for (auto j = ix.segment_offsets[c]; j < ix.segment_offsets[c + 1]; ++j)
          found = std::min(found, segment_polygon_distance(segments_[ix.segment_items[j]], poly));
        for (auto j = ix.circle_offsets[c]; j < ix.circle_offsets[c + 1]; ++j) {
          const Circle& ci = circles_[ix.circle_items[j]];
          const double d = contains(poly, ci.center)
                               ? -ci.radius
                               : boundary_distance(poly, ci.center) - ci.radius;
          found = std::min(found, d);
        }
      }
  }
  // Nothing within reach: the disc about the polygon gives a finite lower bound.
  if (found == kInf && (!segments_.empty() || !circles_.empty()))
    found = std::max(reach, clearance(centre) - radius);
  return std::min(best, found);
}

}  // namespace floornav
