#include "floornav/nav/behaviours.hpp"

#include <algorithm>
#include <cmath>

namespace floornav {

Vec2 go_to_goal_velocity(const Vec2& x, const Vec2& goal, double v0, double a) {
  const Vec2 e = goal - x;  // eq. 5.17
  const double n = e.norm();
  if (n <= 1e-12) return Vec2::Zero();
  // Capped gain, eq. 5.19. Past an exponent of 40, 1 - e^-x rounds to 1 exactly (e^-40 is below
  // half an ulp of 1): the same bits without exp's slow underflow path far from the goal.
  const double x2 = a * n * n;
  const double k = v0 * (x2 > 40.0 ? 1.0 : 1.0 - std::exp(-x2)) / n;
  return k * e;  // eq. 5.18
}

Vec2 avoid_obstacle_velocity(const Vec2& x, std::span<const Vec2> points, double v0) {
  Vec2 sum = Vec2::Zero();
  for (const Vec2& p : points) {
    const Vec2 away = x - p;  // -e, eq. 5.20
    const double d2 = away.squaredNorm();
    if (d2 <= 1e-24) continue;
    sum += avoid_obstacle_term(away, std::sqrt(d2), d2);
  }
  return v0 * normalized_or_zero(sum);
}

double blend_weight(double clearance, double d_near, double d_far) {
  if (d_far <= d_near) return clearance <= d_near ? 1.0 : 0.0;
  const double s = std::clamp((d_far - clearance) / (d_far - d_near), 0.0, 1.0);
  return s * s * (3.0 - 2.0 * s);
}

Vec2 blend_velocities(const Vec2& u_gtg, const Vec2& u_ao, double sigma) {
  return (1.0 - sigma) * u_gtg + sigma * u_ao;  // eq. 5.21, sigma_1 + sigma_2 = 1
}

Vec2 follow_boundary_tangent(const Vec2& u_ao, Turn turn) {
  // R(-pi/2) for clockwise (eq. 5.22), R(+pi/2) for counter-clockwise.
  return turn == Turn::Clockwise ? rotate_cw90(u_ao) : rotate_ccw90(u_ao);
}

Turn choose_turn(const Vec2& u_gtg, const Vec2& u_ao) {
  // An obstacle dead ahead (the two dot products of 5.23/5.24 both zero) leaves the choice to
  // rounding, which can differ between two mirror-image robots meeting head on: they would
  // swerve the same way in the world and collide. A tie, to well above rounding, turns
  // clockwise, so that robots meeting head on both keep to the same side.
  constexpr double kTie = 1e-9;
  const double dot = u_gtg.dot(follow_boundary_tangent(u_ao, Turn::Clockwise));
  return dot > -kTie * u_gtg.norm() * u_ao.norm() ? Turn::Clockwise : Turn::CounterClockwise;
}

Vec2 follow_boundary_velocity(const Vec2& away, double clearance, Turn turn, double d_fb,
                              double k_distance, double v0) {
  const Vec2 tangent = follow_boundary_tangent(away, turn);
  // Positive error: too close, move out along `away`; negative: drifting off, move in. Moving in
  // is capped more gently (at most ~27 degrees off the tangent): sparse range sensors report a
  // convex corner late, and a steep pull towards remembered points would cut the corner.
  constexpr double kMaxPushOut = 1.5, kMaxPullIn = 0.5;
  const double correction = std::clamp(k_distance * (d_fb - clearance), -kMaxPullIn, kMaxPushOut);
  return v0 * normalized_or_zero(tangent + correction * away);
}

}  // namespace floornav
