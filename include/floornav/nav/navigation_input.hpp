#pragma once
/// @file
/// What the supervisor sees at one step, computed once from the sensed obstacle points: the
/// behaviours' vectors u_GTG (eq. 5.18) and u_AO (eq. 5.20), the nearest clearance, the distance
/// to the goal, and the extensions' inputs (the clear-shot corridor, footprint clearance).

#include <limits>
#include <span>

#include "floornav/geometry/vec2.hpp"
#include "floornav/nav/navigation_params.hpp"

namespace floornav {

struct NavigationInput {
  Vec2 x{Vec2::Zero()};      ///< robot position, m
  Vec2 goal{Vec2::Zero()};   ///< current goal, m
  Vec2 u_gtg{Vec2::Zero()};  ///< eq. 5.18
  Vec2 u_ao{Vec2::Zero()};   ///< eq. 5.20; zero when no obstacle is sensed
  Vec2 away{Vec2::Zero()};   ///< u_AO normalised
  double clearance{std::numeric_limits<double>::infinity()};  ///< nearest sensed, from the body
  double goal_distance{0.0};                                  ///< |x - x_g|
  bool obstacle_sensed{false};
  /// A sensed point lies in the corridor towards the goal (NavigationParams::clear_shot_corridor;
  /// false when that test is off).
  bool corridor_blocked{false};
};

/// A robot's footprint polygon (robot frame) and heading, for guards that measure clearance from
/// the footprint (NavigationParams::footprint_clearance).
struct BodyShape {
  std::span<const Vec2> footprint;
  double heading{0.0};  ///< rad
};

/// The step's input from the robot position, goal and sensed obstacle points (world frame).
/// The clearance is from the body disc of `body_radius`, or, with `shape` given and
/// `p.footprint_clearance` on, from the footprint polygon.
NavigationInput make_navigation_input(const Vec2& x, const Vec2& goal,
                                      std::span<const Vec2> obstacle_points, double body_radius,
                                      const NavigationParams& p, const BodyShape* shape = nullptr);

/// No sensed point in the rectangle of half-width `half_width` from x towards the goal, `length`
/// long (or to the goal, if nearer): the body could drive straight at the goal that far.
bool corridor_clear(const Vec2& x, const Vec2& goal, std::span<const Vec2> points, double length,
                    double half_width);

}  // namespace floornav
