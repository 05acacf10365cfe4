#pragma once
/// @file
/// Shortest paths on a raster of free cells: octile A* (8-connected, no corner cutting), raster
/// line of sight and string pulling, and the optimum of a scenario (start through every goal in
/// order, for a disc robot of radius r) on a raster of the world. The batch runner uses it for
/// `path_efficiency` where no benchmark file gives the optimum.
///
/// What the optimum means: a cell is free when the world's clearance at its centre exceeds r
/// (the configuration space, sampled at cell centres). The octile length is therefore an upper
/// bound on the shortest path through free cell centres, up to ~8 % longer than any-angle
/// (cos 22.5 deg); string pulling then shortens it with straight segments that cross only free
/// cells. Both are approximations of the true Euclidean optimum at the raster's resolution, not
/// exact values: see docs/BENCHMARKS.md.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "floornav/core/enum_names.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

class World;

/// A grid of free (nonzero) and blocked (zero) cells, row-major from row iy = 0. In cell units,
/// cell (ix, iy) covers [ix, ix + 1) x [iy, iy + 1) and its centre is (ix + 0.5, iy + 0.5).
struct FreeRaster {
  int width{0};
  int height{0};
  std::vector<std::uint8_t> free;  ///< width * height bytes

  bool is_free(int ix, int iy) const {
    return ix >= 0 && iy >= 0 && ix < width && iy < height &&
           free[static_cast<std::size_t>(iy) * static_cast<std::size_t>(width) +
                static_cast<std::size_t>(ix)] != 0;
  }
};

struct GridCell {
  int x{0};
  int y{0};
  bool operator==(const GridCell&) const = default;
};

struct GridPath {
  double length{0.0};           ///< in cells: 1 per straight step, sqrt(2) per diagonal step
  std::vector<GridCell> cells;  ///< start to goal, both included
};

/// Octile A* from `start` to `goal`: moves to the 8 neighbours, a diagonal move only when both
/// cells it passes between are free (no corner cutting). Empty when either cell is blocked or
/// outside the raster, or the goal is unreachable. Deterministic; iterative; O(n log n).
/// (The search of GridSearch, with working memory kept per thread.)
std::optional<GridPath> octile_astar(const FreeRaster& raster, GridCell start, GridCell goal);

/// Jump point search: an octile path of the same length as octile_astar's (to the rounding of
/// the sums: 1e-12 relative), found by expanding only the jump points (straight runs to a
/// forced turn, diagonal runs to a straight run that finds one), tens of times fewer cells on
/// open floors. Where several paths are shortest, it may take another than octile_astar.
/// Empty when octile_astar's is. The search of scenario_optimum.
std::optional<GridPath> octile_jump_point_search(const FreeRaster& raster, GridCell start,
                                                 GridCell goal);

/// The octile A* of `octile_astar` with its working memory (costs, parents, open list) kept from
/// one search to the next: a planner that searches again and again on rasters of one size
/// allocates nothing after its first search (the cells of the path aside). Entries are
/// invalidated by a search count, not by clearing the buffers; the open list is a radix heap.
class GridSearch {
 public:
  GridSearch();
  ~GridSearch();
  GridSearch(GridSearch&&) noexcept;
  GridSearch& operator=(GridSearch&&) noexcept;

  /// The same path as `octile_astar(raster, start, goal)`, into `path` (its cells vector is
  /// reused). False, with `path` empty, when there is none.
  bool search(const FreeRaster& raster, GridCell start, GridCell goal, GridPath& path);
  /// Cells expanded by the last search (for benchmarks and tests).
  std::size_t expanded() const { return expanded_; }

 private:
  struct Buffers;  // the A* working memory (shortest_path.cpp), reused by every search
  std::unique_ptr<Buffers> buffers_;
  std::size_t expanded_{0};
};

/// The free cell whose centre is nearest to `p` (cell units) within `radius` cells (`p`'s own cell
/// when it is free), ties to the lowest row then column; nullopt when there is none.
std::optional<GridCell> snap_to_free(const FreeRaster& raster, const Vec2& p, double radius);

/// True when every cell whose closed square the segment a-b (cell units) touches is free: a
/// segment along a cell border needs the cells on both sides, one through a corner all four.
bool line_of_sight(const FreeRaster& raster, const Vec2& a, const Vec2& b);

/// Greedy string pulling: drops every vertex of the polyline `points` (cell units) that the
/// previous kept vertex can see past. The result is never longer than the input, and its
/// segments cross only free cells when the input's do.
std::vector<Vec2> pull_string(const FreeRaster& raster, std::span<const Vec2> points);

/// The same greedy string pulling with any line-of-sight test `clear(a, b)` (a planner's test
/// on the world's clearance, say), in whatever frame the points are. Written to `out`.
template <class LineOfSight>
void pull_string(std::span<const Vec2> points, LineOfSight&& clear, std::vector<Vec2>& out) {
  out.clear();
  if (points.empty()) return;
  out.push_back(points[0]);
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
    if (!clear(out.back(), points[i + 1])) out.push_back(points[i]);
  if (points.size() > 1) out.push_back(points.back());
}

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

/// The configuration space of a disc robot on a raster: cell (ix, iy), covering
/// [ix, ix + 1) x [iy, iy + 1) times `cell` in the frame `origin`, is free when
/// `world.clearance` at its centre exceeds `body_radius`. Empty for a non-positive size.
FreeRaster free_cells(const World& world, double body_radius, const Pose2& origin, double cell,
                      int width, int height);

/// `free_cells` over `frame`.
FreeRaster free_cells(const World& world, double body_radius, const RasterFrame& frame);

/// How the optimum of a scenario is computed.
struct OptimumOptions {
  double cell_size{0.05};  ///< m, worlds without an occupancy grid (made finer for small robots)
  std::size_t max_cells{4'000'000};  ///< larger rasters are not built: no optimum
  double snap_radius{3.0};           ///< cells: how far a blocked start/goal looks for a free cell
  bool smooth{true};                 ///< string-pull the octile path
  /// Make the cells no coarser than half the radius (the optimum's accuracy); a planner that
  /// is given its cell size turns this off.
  bool cell_finer_than_radius{true};
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

/// The raster `scenario_optimum` uses for a disc of radius `body_radius` (see there): the
/// occupancy grid's own cells, or square cells over the bounds (or the obstacles, start and goals
/// with a margin). nullopt when it would exceed `options.max_cells` (or need cells coarser than
/// the radius). A planner on the known map plans on the same raster.
std::optional<RasterFrame> choose_raster_frame(const World& world, double body_radius,
                                               const Vec2& start, std::span<const Vec2> goals,
                                               const OptimumOptions& options = {});

/// The shortest collision-free path length for a disc robot of radius `body_radius` from `start`
/// through every goal in order, on a raster of `world`: the occupancy grid's own cells when the
/// world has one (in its frame and resolution), else square cells of `options.cell_size` (or
/// body_radius / 2 if smaller) over the bounds, or over the obstacles, start and goals with a
/// margin. A cell is free when `world.clearance` at its centre exceeds `body_radius`. Each leg runs
/// from the exact point to the nearest free cell centre, along the octile path (of
/// octile_jump_point_search: octile_astar's length, perhaps another of the shortest paths), to the
/// exact goal.
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
