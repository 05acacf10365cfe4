#pragma once
/// @file
/// A footprint-aware safety check of each command against the obstacle points the robot knows
/// (this step's returns plus remembered ones): the robot's footprint polygon is swept along the
/// arc that a unicycle command (V, omega) drives over a short horizon, and the command is changed
/// only when the sweep would come within a margin of a point.
///
/// The rule (Nav2's collision monitor in its "approach" mode, plus a way out when that is too
/// slow):
///   1. t_c = the first time the swept footprint comes within the margin of a point, holding the
///      command (infinite if not within the horizon H);
///   2. t_c >= H: the command is safe as it is;
///   3. else scale V and omega together by s = t_c / H (the same arc, slower: contact is then H
///      away); if s >= min_scale, that is the command;
///   4. else the way is blocked: among a few alternatives (the other turn direction on the spot,
///      backing up straight or turning, creeping straight on) the one with the largest free
///      fraction t_c / H, the nearest to the wanted command among equals; scaled like 3. None
///      free at all: stand still (turning on the spot is never forced into a point).
/// The margin shrinks to half the current clearance when the robot is already closer than the
/// margin, so that it can always move away from a point it is near.
///
/// Without acceleration limits in the simulator the robot can stop within one step, so a short
/// horizon is enough; the check is made against points, so a robot with a blind sector behind it
/// (the Jackal's 270-degree lidar) needs remembered points there (the planner's rolling grid).

#include <span>
#include <vector>

#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// First time (s) at which the footprint polygon `footprint` (robot frame), driving the unicycle
/// arc (v m/s, omega rad/s) from the robot frame's origin, comes within `margin` m of one of
/// `points` (robot frame at t = 0); sampled so that no footprint point moves more than `step` m
/// between samples. Returns 0 when a point is within the margin already, +infinity when none is
/// met within `horizon` s.
double time_to_contact(std::span<const Vec2> footprint, std::span<const Vec2> points, double v,
                       double omega, double horizon, double margin, double step = 0.02);

/// Smallest distance (m) from `points` (robot frame) to the footprint polygon; negative depth
/// for a point inside it; +infinity without points.
double footprint_clearance(std::span<const Vec2> footprint, std::span<const Vec2> points);

struct FootprintGuardParams {
  double horizon{0.5};     ///< s: H
  double margin{0.02};     ///< m kept between the footprint and every point
  double min_scale{0.3};   ///< below this fraction of the wanted speed the way counts as blocked
  double turn_rate{1.0};   ///< rad/s of the alternatives that turn
  double back_speed{0.2};  ///< m/s of the alternatives that back up (and creep on)
};

/// What the guard did with one command.
struct GuardResult {
  double v{0.0};
  double omega{0.0};
  double scale{1.0};     ///< free fraction t_c / H of the wanted command (1: untouched)
  bool replaced{false};  ///< an alternative was chosen (the wanted way was blocked)
};

/// The safety check with its working memory (sized once, reused every step).
class FootprintGuard {
 public:
  FootprintGuard(std::vector<Vec2> footprint, FootprintGuardParams params);

  /// The points (world frame) the next check() runs against, around `pose`: only those that a
  /// sweep within the horizon at up to `reach` m/s could meet are kept, in the robot frame.
  void set_points(const Pose2& pose, std::span<const Vec2> world_points, double reach);
  /// Adds more points (the remembered ones) after set_points, same pose and reach.
  void add_points(std::span<const Vec2> world_points);

  /// The wanted command (v, omega) made safe against the points set (rule above).
  GuardResult check(double v, double omega) const;
  /// Free fraction min(1, t_c / H) of one command.
  double free_fraction(double v, double omega) const;
  /// The current clearance of the footprint from the points set.
  double clearance() const { return footprint_clearance(footprint_, local_); }

  const FootprintGuardParams& params() const { return p_; }
  /// m from the centre within which the last set_points kept points.
  double keep_radius() const { return keep_; }
  std::span<const Vec2> local_points() const { return local_; }

 private:
  double margin_now() const;
  std::vector<Vec2> footprint_;
  FootprintGuardParams p_;
  double circumradius_{0.0};
  Pose2 pose_{};
  double keep_{0.0};  ///< m from the centre within which points are kept
  std::vector<Vec2> local_;
};

}  // namespace floornav
