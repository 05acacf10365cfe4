#pragma once
/// @file
/// Where a raster lies in the world, and the raster a route through a world is planned on: the
/// occupancy grid's own cells, or square cells over the bounds (or over the obstacles, start and
/// goals with a margin).

#include <cstddef>
#include <optional>
#include <span>

#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

class World;

/// Where a raster lies in the world: cell (ix, iy) covers [ix, ix + 1) x [iy, iy + 1) times
/// `cell` metres in the frame `origin`.
struct RasterFrame {
  Pose2 origin{};
  double cell{1.0};  ///< m
  int width{0};
  int height{0};

  Vec2 to_cells(const Vec2& world) const {
    return rotate(world - origin.position, -origin.theta) / cell;
  }
  Vec2 to_world(const Vec2& cells) const { return origin.transform_point(cells * cell); }
};

/// How the raster of a world is chosen.
struct RasterOptions {
  double cell_size{0.05};  ///< m, worlds without an occupancy grid (made finer for small robots)
  std::size_t max_cells{4'000'000};  ///< larger rasters are not built
  /// Make the cells no coarser than half the radius (the optimum's accuracy); a planner that
  /// is given its cell size turns this off.
  bool cell_finer_than_radius{true};
};

/// The raster for a disc of radius `body_radius` routed from `start` through `goals`: the
/// occupancy grid's own cells when the world has one (in its frame and resolution), else square
/// cells of `options.cell_size` (or body_radius / 2 if smaller and `cell_finer_than_radius`) over
/// the bounds, or over the obstacles, start and goals with a margin. nullopt when it would exceed
/// `options.max_cells` (or need cells coarser than the radius), or for a non-finite start, a
/// negative or non-finite radius or a non-positive cell size. The scenario optimum
/// (runner/scenario_optimum.hpp) and a planner on the known map plan on the same raster.
std::optional<RasterFrame> choose_raster_frame(const World& world, double body_radius,
                                               const Vec2& start, std::span<const Vec2> goals,
                                               const RasterOptions& options = {});

}  // namespace floornav
