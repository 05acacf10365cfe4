#include "floornav/world/shortest_path.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

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

FreeRaster rasterise(const World& world, double r, const RasterFrame& f) {
  FreeRaster raster;
  raster.width = f.width;
  raster.height = f.height;
  raster.free.assign(static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height), 0);
  const OccupancyGrid* grid = world.grid();
  // Clearance is 1-Lipschitz: a centre with clearance c decides the next cells of its row up to
  // |c - r| away without more queries (free ones stay above r, blocked ones at most r). The
  // margin keeps a rounding error from flipping a cell that a query would decide otherwise.
  constexpr double kMargin = 1e-9;
  const double max_skip = static_cast<double>(f.width);
  for (int iy = 0; iy < f.height; ++iy) {
    const std::size_t row = static_cast<std::size_t>(iy) * static_cast<std::size_t>(f.width);
    for (int ix = 0; ix < f.width;) {
      // An occupied map cell is blocked whatever else the world holds: skip the query.
      if (grid && grid->occupied(ix, iy)) {
        ++ix;
        continue;
      }
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
  return raster;
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
  return rasterise(world, body_radius, frame);
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
  return rasterise(world, body_radius, RasterFrame{origin, cell, width, height});
}

std::optional<GridPath> octile_astar(const FreeRaster& raster, GridCell start, GridCell goal) {
  GridSearch search;
  GridPath path;
  if (!search.search(raster, start, goal, path)) return std::nullopt;
  return path;
}

void GridSearch::fit(std::size_t cells) {
  if (g_.size() < cells) {
    g_.resize(cells);
    parent_.resize(cells);
    seen_.resize(cells, 0);
    closed_.resize(cells, 0);
  }
  if (++generation_ == 0) {  // wrapped round: old stamps could look current
    std::fill(seen_.begin(), seen_.end(), 0);
    std::fill(closed_.begin(), closed_.end(), 0);
    generation_ = 1;
  }
  open_.clear();
}

bool GridSearch::search(const FreeRaster& raster, GridCell start, GridCell goal, GridPath& path) {
  path.length = 0.0;
  path.cells.clear();
  expanded_ = 0;
  if (!raster.is_free(start.x, start.y) || !raster.is_free(goal.x, goal.y)) return false;
  const std::size_t w = static_cast<std::size_t>(raster.width);
  fit(w * static_cast<std::size_t>(raster.height));
  const std::uint32_t gen = generation_;
  auto index = [w](int x, int y) {
    return static_cast<std::size_t>(y) * w + static_cast<std::size_t>(x);
  };
  auto g_of = [&](std::size_t v) { return seen_[v] == gen ? g_[v] : kInf; };
  // (f, -g, index): lowest f first; among equal f the deepest node, then the lowest index, so
  // the order (and the path) is deterministic. A binary heap on a kept vector.
  const auto later = std::greater<Entry>();
  auto push = [&](Entry e) {
    open_.push_back(e);
    std::push_heap(open_.begin(), open_.end(), later);
  };
  const std::size_t s = index(start.x, start.y), t = index(goal.x, goal.y);
  g_[s] = 0.0;
  parent_[s] = -1;
  seen_[s] = gen;
  push({octile_distance(goal.x - start.x, goal.y - start.y), -0.0, s});
  constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  while (!open_.empty()) {
    std::pop_heap(open_.begin(), open_.end(), later);
    const std::size_t u = open_.back().index;
    open_.pop_back();
    if (closed_[u] == gen) continue;
    closed_[u] = gen;
    ++expanded_;
    if (u == t) break;
    const int ux = static_cast<int>(u % w), uy = static_cast<int>(u / w);
    const double gu = g_[u];
    for (int k = 0; k < 8; ++k) {
      const int vx = ux + kDx[k], vy = uy + kDy[k];
      if (!raster.is_free(vx, vy)) continue;
      const bool diagonal = kDx[k] != 0 && kDy[k] != 0;
      if (diagonal && (!raster.is_free(ux + kDx[k], uy) || !raster.is_free(ux, uy + kDy[k])))
        continue;  // no corner cutting
      const std::size_t v = index(vx, vy);
      if (closed_[v] == gen) continue;
      const double gv = gu + (diagonal ? kSqrt2 : 1.0);
      if (gv < g_of(v)) {
        g_[v] = gv;
        parent_[v] = static_cast<std::int32_t>(u);
        seen_[v] = gen;
        push({gv + octile_distance(goal.x - vx, goal.y - vy), -gv, v});
      }
    }
  }
  if (closed_[t] != gen) return false;
  path.length = g_[t];
  for (std::int64_t v = static_cast<std::int64_t>(t); v >= 0;
       v = parent_[static_cast<std::size_t>(v)])
    path.cells.push_back({static_cast<int>(static_cast<std::size_t>(v) % w),
                          static_cast<int>(static_cast<std::size_t>(v) / w)});
  std::reverse(path.cells.begin(), path.cells.end());
  return true;
}

bool line_of_sight(const FreeRaster& raster, const Vec2& a, const Vec2& b) {
  if (!is_finite(a) || !is_finite(b)) return false;
  constexpr double kEps = 1e-9;  // a touch of a border or corner counts (conservative)
  const Vec2 lo = a.x() <= b.x() ? a : b;
  const Vec2 hi = a.x() <= b.x() ? b : a;
  const double dx = hi.x() - lo.x();
  const int x0 = static_cast<int>(std::floor(lo.x() - kEps));
  const int x1 = static_cast<int>(std::floor(hi.x() + kEps));
  for (int ix = x0; ix <= x1; ++ix) {
    // The part of the segment within column ix (widened by kEps), then the rows it spans.
    const double xa = std::max(lo.x(), ix - kEps), xb = std::min(hi.x(), ix + 1 + kEps);
    double ya = lo.y(), yb = hi.y();
    if (dx > 0.0) {
      const double slope = (hi.y() - lo.y()) / dx;
      ya = lo.y() + slope * (xa - lo.x());
      yb = lo.y() + slope * (xb - lo.x());
    }
    if (ya > yb) std::swap(ya, yb);
    const int y0 = static_cast<int>(std::floor(ya - kEps));
    const int y1 = static_cast<int>(std::floor(yb + kEps));
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

std::string_view to_string(OptimumStatus s) {
  switch (s) {
    case OptimumStatus::Found:
      return "found";
    case OptimumStatus::Unreachable:
      return "unreachable";
    case OptimumStatus::NoFreeCell:
      return "no_free_cell";
    case OptimumStatus::RasterTooLarge:
      return "raster_too_large";
    case OptimumStatus::InvalidInput:
      return "invalid_input";
  }
  return "invalid_input";
}

Optimum scenario_optimum(const World& world, double body_radius, const Vec2& start,
                         std::span<const Vec2> goals, const OptimumOptions& options) {
  Optimum out;
  if (goals.empty() || !is_finite(start) || !std::isfinite(body_radius) || body_radius < 0.0 ||
      !(options.cell_size > 0.0) ||
      !std::all_of(goals.begin(), goals.end(), [](const Vec2& g) { return is_finite(g); }))
    return out;
  const auto frame = choose_frame(world, body_radius, start, goals, options);
  if (!frame) {
    out.status = OptimumStatus::RasterTooLarge;
    return out;
  }
  out.cell_size = frame->cell;
  out.width = frame->width;
  out.height = frame->height;
  const FreeRaster raster = rasterise(world, body_radius, *frame);

  double length = 0.0, octile = 0.0;
  std::vector<Vec2> route;
  Vec2 from = frame->to_cells(start);
  auto from_cell = snap_to_free(raster, from, options.snap_radius);
  for (const Vec2& goal_world : goals) {
    const Vec2 to = frame->to_cells(goal_world);
    const auto to_cell = snap_to_free(raster, to, options.snap_radius);
    if (!from_cell || !to_cell) {
      out.status = OptimumStatus::NoFreeCell;
      return out;
    }
    const auto path = octile_astar(raster, *from_cell, *to_cell);
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
      route.push_back(frame->to_world(points[i]));
    from = to;
    from_cell = to_cell;
  }
  out.status = OptimumStatus::Found;
  out.length = length * frame->cell;
  out.octile_length = octile * frame->cell;
  out.path = std::move(route);
  return out;
}

}  // namespace floornav
