#pragma once
/// @file
/// The point-robot behaviours of sections 5.3-5.4: each returns a velocity u (m/s, world frame)
/// for the point-mass model x' = u (eq. 5.16). The differential-drive pipeline
/// (heading_tracker.hpp) turns u into wheel speeds.

#include <span>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// Go to goal (eqs. 5.16-5.19): e = x_g - x, u = K e with the capped gain
/// K = v0 (1 - exp(-a |e|^2)) / |e|: speed v0 far away, a smooth stop at the goal.
Vec2 go_to_goal_velocity(const Vec2& x, const Vec2& goal, double v0, double a);

/// Avoid obstacle (eq. 5.20) from sensed obstacle points: the weighted sum of the away-vectors
/// (x - x_o)/|x - x_o|, weight 1/(|x - x_o|^2 + eps) so that near points count most, scaled to
/// speed v0. Zero when there are no points.
Vec2 avoid_obstacle_velocity(const Vec2& x, std::span<const Vec2> points, double v0);

/// One point's term of avoid_obstacle_velocity's sum (eq. 5.20), from `away` = x - x_o, its
/// squared length `d2` and length `d` = sqrt(d2). A point with d2 <= 1e-24 (on x) adds nothing:
/// callers skip it.
inline Vec2 avoid_obstacle_term(const Vec2& away, double d, double d2) {
  constexpr double kEps = 1e-3;  // m^2: keeps the weight finite on contact
  return away / (d * (d2 + kEps));
}

/// Blending (eq. 5.21): u = (1 - sigma) u_gtg + sigma u_ao, with sigma rising from 0 at
/// clearance `d_far` to 1 at clearance `d_near` (smoothstep).
double blend_weight(double clearance, double d_near, double d_far);
Vec2 blend_velocities(const Vec2& u_gtg, const Vec2& u_ao, double sigma);

/// Which way round the obstacle follow-boundary goes (eqs. 5.22-5.24).
enum class Turn { Clockwise, CounterClockwise };

/// Follow boundary (eqs. 5.22-5.24): the avoid direction rotated by -pi/2 (clockwise) or +pi/2
/// (counter-clockwise), plus a correction along the avoid direction that holds the clearance
/// at `d_fb` (pushes out when closer, pulls in when farther), scaled to speed v0.
/// `away` is the unit vector pointing away from the obstacle (u_AO normalised).
Vec2 follow_boundary_velocity(const Vec2& away, double clearance, Turn turn, double d_fb,
                              double k_distance, double v0);

/// The tangent alone, alpha R(-+pi/2) u_AO with alpha = 1: the vectors compared with u_GTG by
/// eqs. 5.23/5.24.
Vec2 follow_boundary_tangent(const Vec2& u_ao, Turn turn);

/// Eqs. 5.23/5.24: clockwise when <u_gtg, u_fb^c> > 0, otherwise counter-clockwise.
Turn choose_turn(const Vec2& u_gtg, const Vec2& u_ao);

}  // namespace floornav
