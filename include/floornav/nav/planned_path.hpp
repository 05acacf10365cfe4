#pragma once
/// @file
/// A planned path (a polyline, world frame) as the robot follows it: where the robot is along it
/// (a projection that only moves forward), how much of it is left, and the subgoal handed to the
/// automaton: `lookahead` metres further along, but not round the next corner before the robot
/// has come within `corner` of it (so the straight line to the subgoal does not cut the corner
/// the path was pulled tight against).

#include <cstddef>
#include <span>
#include <vector>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

class PlannedPath {
 public:
  /// A new path, start to goal (at least one point); the projection goes back to its start.
  void assign(std::span<const Vec2> points);
  void clear();
  bool empty() const { return points_.empty(); }
  std::span<const Vec2> points() const { return points_; }
  double length() const { return arc_.empty() ? 0.0 : arc_.back(); }

  /// Moves the projection to the point of the path nearest to `p` among the segments from the
  /// current one to `ahead` metres beyond it (never backwards). Returns the distance from `p` to
  /// the path.
  double project(const Vec2& p, double ahead);
  /// m along the path of the projection.
  double progress() const { return s_; }
  /// m of path left after the projection.
  double remaining() const { return length() - s_; }
  /// The segment the projection is on (points()[segment()] to points()[segment() + 1]).
  std::size_t segment() const { return segment_; }

  /// The subgoal for a robot at `p`: the point `lookahead` m beyond the projection, but no
  /// further than the next vertex unless `p` is within `corner` of it, and then no further than
  /// the vertex after it. The last point when the path ends sooner.
  Vec2 subgoal(const Vec2& p, double lookahead, double corner) const;

  /// The point `s` m along the path (clamped to its ends).
  Vec2 point_at(double s) const;

 private:
  std::vector<Vec2> points_;
  std::vector<double> arc_;  ///< arc_[i]: m along the path at points_[i]
  std::size_t segment_{0};
  double s_{0.0};
};

}  // namespace floornav
