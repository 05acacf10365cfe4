#pragma once
/// @file
/// The dynamic window approach (Fox, Burgard, Thrun 1997) as a controller kind (`dwa`), the
/// baseline the chapter's automaton and the planning layer are measured against. Each step:
///   1. window: the (v, omega) reachable within one step from the last command under the robot's
///      acceleration limits (RobotSpec::max_acceleration, max_angular_acceleration), within
///      0 <= v <= v0 (and what the wheels allow while turning) and |omega| <= the base's;
///   2. obstacles: the sensed points within `range` go into a local distance map (exact
///      Euclidean distance transform of their cells);
///   3. roll-out: each of v_samples x omega_samples candidates is driven along its exact arc for
///      `horizon` seconds, its footprint (discs covering the polygon, or the body disc) checked
///      every sim_step; `dist` is the arc length driven before the first pose closer than
///      `margin` to an obstacle (infinite when none);
///   4. admissible: the robot could brake to a stop before that pose (eq. 14 of the paper:
///      the time to it exceeds max(v / a, |omega| / alpha) plus a step);
///   5. score (eq. 15): G = alpha heading + beta dist + gamma velocity, each in [0, 1]:
///      heading = 1 - |angle to the goal at the end of the roll-out| / pi (judged after at most
///      a quarter turn), dist = min(dist, max_clearance) / max_clearance, velocity = v / v0
///      (see dwa_score). Standing still is not a candidate (it would score best in front of any
///      obstacle on the goal line);
///      the best admissible candidate is driven (a unicycle command). With none admissible it
///      brakes and turns towards the goal (mode `dwa_brake`).
/// Speed is capped at sqrt(2 a d) at distance d from the goal, so it stops there.

#include <span>
#include <vector>

#include "floornav/nav/controller.hpp"

namespace floornav {

/// The most discs a footprint may take to cover (one per width along its long side: a footprint
/// 64 times as long as it is wide). Each disc is checked at every pose of every roll-out.
inline constexpr double kMaxDwaFootprintDiscs = 64;
/// The most footprint checks one step of the controller may make: v_samples x omega_samples x
/// poses per roll-out x discs (the defaults: 9 x 21 x 20 x 1 = 3780). About 10 ms a step at the
/// limit; validate_scenario refuses settings beyond it before the controller is made.
inline constexpr double kMaxDwaChecksPerStep = 1e6;

/// How many discs cover `footprint` (robot frame): ceil(long side / short side) of its box, 1 for
/// the body disc (an empty footprint). A double, so that a sliver's count does not overflow.
double dwa_footprint_discs(std::span<const Vec2> footprint);
/// Poses checked along one roll-out: ceil(horizon / sim_step), at least 1.
double dwa_roll_out_poses(const DwaParams& p);

/// Eq. 15 for one candidate: `heading_error` rad (the goal's bearing at the end of the
/// roll-out), `dist` m driven before a collision (infinity: none), speed `v` of `v_max`.
double dwa_score(const DwaParams& p, double heading_error, double dist, double v, double v_max);

class DwaController final : public Controller {
 public:
  /// `params` for v0 and epsilon, `dwa` for the window and the objective.
  DwaController(const NavigationParams& params, const DwaParams& dwa, const RobotSpec& robot);

  Decision decide(const Observation& obs) override;
  void reset() override;
  int mode() const override { return mode_; }

  /// The last command driven (v m/s, omega rad/s): the centre of the next window.
  UnicycleCommand velocity() const { return {v_, w_}; }

 private:
  struct Disc {
    Vec2 centre;  ///< robot frame
    double radius;
  };
  /// Distance (m) from world point p to the nearest mapped obstacle (infinity off the map).
  double distance(const Vec2& p) const;
  void build_distance_map(const Vec2& centre, std::span<const Vec2> points);

  NavigationParams nav_;
  DwaParams p_;
  const RobotSpec* robot_;
  std::vector<Disc> discs_;
  double v_max_{0.0};
  double w_max_{0.0};
  double range_{0.0};
  // The local distance map: side_ x side_ cells of cell_ m, lower-left corner at origin_.
  double cell_{0.05};
  int side_{0};
  Vec2 origin_{Vec2::Zero()};
  std::vector<double> dist2_;      ///< squared distance in cells^2 to the nearest obstacle cell
  std::vector<double> f_, d_, z_;  ///< transform scratch
  std::vector<int> v_idx_;
  bool any_obstacle_{false};
  double v_{0.0};
  double w_{0.0};
  int mode_{0};
};

}  // namespace floornav
