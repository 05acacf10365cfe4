#include "floornav/runner/scenario_optimum.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "floornav/planning/free_cells.hpp"
#include "floornav/planning/jump_point_search.hpp"
#include "floornav/planning/string_pulling.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

double polyline_length(std::span<const Vec2> points) {
  double sum = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) sum += (points[i] - points[i - 1]).norm();
  return sum;
}

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
  free_cells_into(world, body_radius, *frame, r.raster);
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
              choose_raster_frame(world, body_radius, any, std::span<const Vec2>(&any, 1), options),
              out);
  return true;
}

Optimum scenario_optimum(const World& world, double body_radius, const Vec2& start,
                         std::span<const Vec2> goals, const OptimumOptions& options) {
  if (!valid_route(start, goals) || !valid_radius(body_radius, options)) return {};
  thread_local OptimumRaster raster;  // its memory serves every call on this thread
  make_raster(world, body_radius, choose_raster_frame(world, body_radius, start, goals, options),
              raster);
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
