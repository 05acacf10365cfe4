#pragma once
/// @file
/// The optimum of a scenario, an evaluation metric: the shortest collision-free path length for a
/// disc robot from its start through every goal in order, on a raster of the world. The batch
/// runner uses it for `path_efficiency` where no benchmark file gives the optimum.
///
/// What the optimum means: a cell is free when the world's clearance at its centre exceeds r
/// (the configuration space, sampled at cell centres). The octile length is therefore an upper
/// bound on the shortest path through free cell centres, up to ~8 % longer than any-angle
/// (cos 22.5 deg); string pulling then shortens it with straight segments that cross only free
/// cells. Both are approximations of the true Euclidean optimum at the raster's resolution, not
/// exact values: see docs/BENCHMARKS.md.

#include <span>
#include <vector>

#include "floornav/core/enum_names.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/vec2.hpp"
#include "floornav/planning/free_raster.hpp"
#include "floornav/planning/raster_frame.hpp"

namespace floornav {

class World;

/// How the optimum of a scenario is computed: the raster (RasterOptions), then the search.
struct OptimumOptions : RasterOptions {
  double snap_radius{3.0};  ///< cells: how far a blocked start/goal looks for a free cell
  bool smooth{true};        ///< string-pull the octile path
};

enum class OptimumStatus {
  Found,
  Unreachable,     ///< a goal cannot be reached from the previous one on the raster
  NoFreeCell,      ///< no free cell within the snap radius of the start or a goal
  RasterTooLarge,  ///< the world needs more than max_cells cells (or cells coarser than r)
  InvalidInput,    ///< non-finite point or radius, or no goals
};

inline constexpr EnumName<OptimumStatus> kOptimumStatusNames[]{
    {OptimumStatus::Found, "found"},
    {OptimumStatus::Unreachable, "unreachable"},
    {OptimumStatus::NoFreeCell, "no_free_cell"},
    {OptimumStatus::RasterTooLarge, "raster_too_large"},
    {OptimumStatus::InvalidInput, "invalid_input"}};
constexpr std::span<const EnumName<OptimumStatus>> enum_names(OptimumStatus) {
  return kOptimumStatusNames;
}

struct Optimum {
  OptimumStatus status{OptimumStatus::InvalidInput};
  double length{0.0};         ///< m: string-pulled (or octile when smooth is off); 0 unless Found
  double octile_length{0.0};  ///< m: the octile paths themselves
  double cell_size{0.0};      ///< m, of the raster used
  int width{0};               ///< raster size in cells
  int height{0};
  std::vector<Vec2>
      path;  ///< world frame: start, the kept vertices, every goal; empty unless Found
};

/// The shortest collision-free path length for a disc robot of radius `body_radius` from `start`
/// through every goal in order, on the raster of `world` that choose_raster_frame gives
/// (planning/raster_frame.hpp). A cell is free when `world.clearance` at its centre exceeds
/// `body_radius`. Each leg runs from the exact point to the nearest free cell centre, along the
/// octile path (of octile_jump_point_search: octile_astar's length, perhaps another of the
/// shortest paths), to the exact goal.
Optimum scenario_optimum(const World& world, double body_radius, const Vec2& start,
                         std::span<const Vec2> goals, const OptimumOptions& options = {});

/// The raster scenario_optimum searches, for one world and robot radius: built once, it serves
/// every route in that world (a batch's cases that share a world share it).
struct OptimumRaster {
  OptimumStatus status{OptimumStatus::InvalidInput};  ///< Found when built; else why not
  Pose2 origin{};    ///< cell (ix, iy) covers [ix, ix + 1) x [iy, iy + 1) times `cell` here
  double cell{0.0};  ///< m
  FreeRaster raster;
};

/// Builds into `out` (reusing its memory) the raster of `world` for `body_radius`, when it does
/// not depend on the route: for worlds with bounds or an occupancy grid. False, `out` unchanged,
/// for a world without either (its raster spans the route).
bool build_optimum_raster(const World& world, double body_radius, const OptimumOptions& options,
                          OptimumRaster& out);

/// scenario_optimum on a raster from build_optimum_raster: the same result as scenario_optimum on
/// the world and radius the raster was built for, with the same options.
Optimum scenario_optimum(const OptimumRaster& raster, const Vec2& start,
                         std::span<const Vec2> goals, const OptimumOptions& options = {});

}  // namespace floornav
