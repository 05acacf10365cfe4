#pragma once
/// @file
/// An occupancy map (ROS map_server, MovingAI, a rasterised floor plan) with fast ray casting
/// (DDA ray marching) and clearance (a Euclidean distance transform computed once).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <stdexcept>
#include <utility>
#include <vector>

#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/vec2.hpp"
#include "floornav/world/fan_scratch.hpp"

namespace floornav {

/// A grid of square cells, each free or occupied. Cell (ix, iy) covers
/// `[ix, ix+1) x [iy, iy+1)` times `resolution` in the grid frame, whose pose in the world is
/// `origin` (the lower-left corner of cell (0, 0), with yaw, as in a ROS map yaml).
/// Row iy = 0 is the bottom row (a ROS image's last line). Immutable after construction.
class OccupancyGrid {
 public:
  /// `occupied` holds width * height bytes, row-major from the bottom row; nonzero = occupied.
  /// Throws std::invalid_argument for sizes that do not match or are not positive.
  OccupancyGrid(int width, int height, double resolution, Pose2 origin,
                std::vector<std::uint8_t> occupied);

  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  const Pose2& origin() const { return origin_; }
  bool occupied(int ix, int iy) const;  ///< cells outside the grid count as free
  std::size_t occupied_count() const;

  /// Distance along unit `dir` (world frame) from `origin_world` to the first occupied cell, or
  /// `max_range` (>= 0). 0 when starting in an occupied cell. Exact (cell edges, not samples):
  /// a DDA walk over the cells, clipped to the grid first when starting outside. A ray through a
  /// cell corner also hits the two cells that share it. Non-finite input gives `max_range`.
  double cast_ray(const Vec2& origin_world, const Vec2& dir, double max_range) const;

  /// Casts a fan of rays from one origin: `out[i]` is bit for bit
  /// `cast_ray(origin_world, dirs[i], max_range)`. `angles[i]` is the world angle of `dirs[i]` to
  /// within 1e-9 rad. When the angles are evenly spaced (a lidar) and the origin is in a free cell
  /// of the grid or outside it, the runs of occupied cells that a walk can enter first (those with
  /// a free side facing the origin) within `max_range` are gathered once and each is tested only
  /// against the beams its angular extent covers: for each, the few cells of the run near the
  /// beam's crossing are tested with the walk's own boundary quotients. Anything else is cast ray
  /// by ray. The three spans have the same size. Works in `scratch` (see FanScratch): no allocation
  /// once it has grown to the fan.
  void cast_fan(const Vec2& origin_world, std::span<const Vec2> dirs,
                std::span<const double> angles, double max_range, std::span<double> out,
                FanScratch& scratch) const;
  /// `cast_fan` with scratch memory of its own (allocated per call).
  void cast_fan(const Vec2& origin_world, std::span<const Vec2> dirs,
                std::span<const double> angles, double max_range, std::span<double> out) const;

  /// `cast_ray` walking every cell (no skipping of free space): the oracle for tests. The two
  /// agree bit for bit.
  double cast_ray_cell_by_cell(const Vec2& origin_world, const Vec2& dir, double max_range) const;

  /// Signed distance (m) from `p` (world) to the nearest occupied cell's square, exact also for
  /// points outside the grid. Inside an occupied cell it is minus the distance to that cell's own
  /// border (so only a lower bound on the depth inside a thick wall). +infinity when no cell is
  /// occupied; NaN for a non-finite `p`. Cost O(clearance / resolution).
  double clearance(const Vec2& p) const;

  /// The world-frame point of the nearest occupied square (the point `clearance` measures to).
  bool nearest_occupied_point(const Vec2& p, Vec2* out) const;

  /// World-frame axis-aligned box holding the whole grid.
  void world_extent(Vec2* min, Vec2* max) const;

  /// Marks the cells a map leaves unknown (neither known free nor known occupied): `unknown`
  /// holds width * height bytes like `occupied` (nonzero = unknown), or nothing. For pictures
  /// only: the simulator sees each cell as free or occupied, as the loader's policy made it. Set
  /// by the loader before the grid is shared. Throws std::invalid_argument for a wrong size.
  void set_unknown(std::vector<std::uint8_t> unknown) {
    if (!unknown.empty() &&
        unknown.size() != static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_))
      throw std::invalid_argument("OccupancyGrid: unknown layer of the wrong size");
    unknown_ = std::move(unknown);
  }
  /// True for a cell marked unknown by set_unknown (cells outside the grid are not).
  bool unknown(int ix, int iy) const {
    return !unknown_.empty() && ix >= 0 && iy >= 0 && ix < width_ && iy < height_ &&
           unknown_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(width_) +
                    static_cast<std::size_t>(ix)] != 0;
  }
  bool has_unknown() const { return !unknown_.empty(); }

  /// Row-major index (iy * width + ix) of the occupied cell whose centre is nearest to the centre
  /// of cell (ix, iy) (exact Euclidean feature transform; ties broken arbitrarily), or -1 when no
  /// cell is occupied or (ix, iy) is outside the grid.
  std::int32_t nearest_occupied_index(int ix, int iy) const;

  /// What cast_fan tests, built with the grid: the runs of occupied cells by tile. Opaque (it is
  /// floornav's own, for its fans and their tests); copies of the grid share it.
  struct FanIndex;
  const FanIndex& fan_index() const { return *fan_index_; }

 private:
  Vec2 to_grid(const Vec2& world) const;  // metres, grid frame
  Vec2 to_world(const Vec2& grid) const;  // inverse of to_grid
  /// The distance transform (nearest_, column_nearest_) and the free runs it gives.
  void compute_distance_transform();
  void compute_free_run();
  /// The runs of occupied cells that the fan tests (fan_index_).
  void compute_boundary();
  /// The stages of compute_boundary and of one cast_fan call (grid_fan.cpp).
  struct BoundaryBuild;
  class FanCast;
  /// `cast_ray`; with `skip`, free space is crossed `free_run_` cells at a time.
  double cast(const Vec2& origin_world, const Vec2& dir, double max_range, bool skip) const;
  /// The walk of `cast` with `skip`, from cell (ix, iy) entered at t0; cell units, grid frame.
  double walk_with_jumps(const Vec2& o, const Vec2& d, double max_range, double t_max, double t0,
                         int ix, int iy) const;
  /// Whether grid-frame point (px, py), in cell units, lies in an occupied cell.
  bool in_occupied_cell(double px, double py) const;
  /// Exact nearest occupied square to grid-frame point (px, py) in cell units: returns the squared
  /// distance in cells^2 (+inf if none) and the cell index in `*cell`.
  double nearest_square(double px, double py, std::int32_t* cell) const;
  int width_;
  int height_;
  double resolution_;
  Pose2 origin_;
  std::vector<std::uint8_t> occupied_;
  std::vector<std::uint8_t> unknown_;  ///< for pictures: see set_unknown (empty: none known)
  /// For each cell, the index of the nearest occupied cell (by centre distance), -1 if none.
  std::vector<std::int32_t> nearest_;
  /// For each cell (ix, iy): 2 * r + tie, where r is the nearest occupied row in column ix
  /// (the lower one on a tie) and tie = 1 when row 2 * iy - r is occupied too; -1 if the column
  /// is empty. Pass 1 of the transform, kept for exact point queries (clearance).
  std::vector<std::int32_t> column_nearest_;
  /// For each cell, in 1/16 cell (up to 4096 cells), how far any ray entering the cell travels
  /// before it can touch an occupied square: the centre distance to the nearest occupied centre
  /// minus 1.5. `cast_ray` jumps that far at once.
  std::vector<std::uint16_t> free_run_;
  std::shared_ptr<const FanIndex> fan_index_;  ///< built by compute_boundary
  std::size_t occupied_count_{0};
  double cos_yaw_{1.0};
  double sin_yaw_{0.0};
};

}  // namespace floornav
