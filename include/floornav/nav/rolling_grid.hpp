#pragma once
/// @file
/// A rolling occupancy grid built from a robot's own range readings: a square window of cells
/// that moves with the robot. Each reading marks the cells along its beam as free and the cell at
/// its end as occupied; what is not seen again fades. It is the map of mapless navigation (the
/// planner on the sensed map) and the memory that lets a robot with few sensors keep away from
/// what it saw a while ago.
///
/// Evidence per cell is a small integer e in [-2, 4] (0: unknown):
///   a return in the cell (one scan):       e := min(4, max(e, 0) + 2)  -> occupied at once
///   a beam through the cell (once a scan): e := max(-2, e - 1)         (not in cells hit that
///   scan) occupied when e >= 2; every `decay` seconds without an update, |e| shrinks by 1.
/// So one return makes a cell occupied, a second one makes it take three clear beams (or
/// 2 x decay seconds unseen) to stop being occupied, and a single stray return is cleared by one
/// beam through it. Each occupied cell also keeps its latest return point (exact, not the cell
/// centre): the memory gives the automaton those points.
///
/// Cells are addressed by global indices (floor(x / cell), floor(y / cell)); the window holds
/// side x side of them in a ring buffer, so moving it only forgets the cells it leaves. No
/// allocation after construction.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "floornav/geometry/vec2.hpp"
#include "floornav/planning/free_raster.hpp"
#include "floornav/sensing/range_sensor.hpp"

namespace floornav {

class RollingGrid {
 public:
  static constexpr int kHitGain = 2;
  static constexpr int kMaxEvidence = 4;
  static constexpr int kMinEvidence = -2;
  static constexpr int kOccupied = 2;

  /// `cell` m, `side` cells across (>= 4), `decay` s (> 0). The window starts centred on
  /// `centre`.
  RollingGrid(double cell, int side, double decay, const Vec2& centre = Vec2::Zero());

  double cell() const { return cell_; }
  int side() const { return side_; }
  /// Global index of the window's lower-left cell.
  GridCell origin() const { return origin_; }
  /// The global cell holding `p`.
  GridCell cell_of(const Vec2& p) const;
  Vec2 centre_of(GridCell c) const { return Vec2((c.x + 0.5) * cell_, (c.y + 0.5) * cell_); }
  bool in_window(GridCell c) const {
    return c.x >= origin_.x && c.y >= origin_.y && c.x < origin_.x + side_ &&
           c.y < origin_.y + side_;
  }

  /// Moves the window so that `p` is at its centre when `p` has strayed more than a quarter of
  /// the window from it; the cells it leaves are forgotten (unknown).
  void follow(const Vec2& p);

  /// One scan at time `t` (s, non-decreasing): each beam with its range, up to `sense_range`
  /// (> 0) or the sensor's max range, whichever is less; a range below both is a return.
  void update(std::span<const SensorBeam> beams, std::span<const double> ranges,
              std::span<const RangeSensorSpec> sensors, double sense_range, double t);

  /// The evidence of global cell `c` at time `t`, decay applied (0 outside the window).
  int evidence(GridCell c, double t) const;
  bool occupied(GridCell c, double t) const { return evidence(c, t) >= kOccupied; }
  /// Occupied cells in the window at time `t`.
  std::size_t occupied_count(double t) const;

  /// The planning raster of the window at time `t`: raster cell (i, j) is global cell
  /// origin + (i, j), free unless an occupied cell's return point lies within `radius` m of its
  /// centre. Unknown cells are free (optimistic: the plan goes where nothing was seen).
  /// `out` is resized once and reused.
  void inflate(double radius, double t, FreeRaster& out) const;

  /// Writes the return points of occupied cells within `range` m of `p` to `out` (nearest cells
  /// first would cost a sort: they come in cell order); returns how many (at most out.size()).
  std::size_t remembered_points(const Vec2& p, double range, double t, std::span<Vec2> out) const;

  /// Forgets everything (all cells unknown); the window stays where it is.
  void clear();

 private:
  std::size_t slot(GridCell c) const;
  /// Evidence after decay since the cell's last update.
  int decayed(std::size_t i, double t) const;
  void forget_column(int gx);
  void forget_row(int gy);
  void pass(GridCell c, double t);
  void hit(GridCell c, const Vec2& p, double t);

  double cell_;
  int side_;
  double decay_;
  GridCell origin_{};
  std::vector<std::int8_t> evidence_;
  std::vector<float> updated_;        ///< s: time of the last update
  std::vector<std::uint32_t> scan_;   ///< the scan that last passed or hit the cell
  std::vector<float> hit_x_, hit_y_;  ///< m: latest return in the cell
  std::uint32_t scan_count_{0};
};

}  // namespace floornav
