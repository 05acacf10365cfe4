#include <gtest/gtest.h>

#include <cmath>

#include "floornav/geometry/angle.hpp"
#include "floornav/nav/behaviours.hpp"
#include "floornav/nav/heading_tracker.hpp"
#include "floornav/nav/pid.hpp"

using namespace floornav;

// Eqs. 5.12-5.15: kp = 2, ki = 0.5, kd = 0.1, dt = 0.1. First step e = 0.4:
// integral = 0.04, no derivative yet: omega = 0.8 + 0.02 = 0.82.
// Second step e = 0.2: integral = 0.06, de/dt = -2: omega = 0.4 + 0.03 - 0.2 = 0.23.
TEST(Pid, Eq5_15HandWorked) {
  const PidGains g{2.0, 0.5, 0.1, 10.0};
  PidState s;
  EXPECT_NEAR(pid_step(g, s, 0.4, 0.1), 0.82, 1e-12);
  EXPECT_NEAR(pid_step(g, s, 0.2, 0.1), 0.23, 1e-12);
}

TEST(Pid, AntiWindupClampsTheIntegral) {
  const PidGains g{0.0, 1.0, 0.0, 0.5};
  PidState s;
  for (int i = 0; i < 100; ++i) pid_step(g, s, 1.0, 0.1);
  EXPECT_DOUBLE_EQ(s.integral, 0.5);
  EXPECT_DOUBLE_EQ(pid_step(g, s, 1.0, 0.1), 0.5);
}

TEST(Pid, DerivativeAcrossPiIsNotASpike) {
  const PidGains g{0.0, 0.0, 1.0, 1.0};
  PidState s;
  pid_step(g, s, kPi - 0.01, 0.1);
  // The error wrapped from just below pi to just above -pi: a change of 0.02 rad, not 2 pi.
  EXPECT_NEAR(pid_step(g, s, -kPi + 0.01, 0.1), 0.2, 1e-9);
}

// Eq. 5.14 in the heading loop: theta_d = atan2(1, -1) = 3pi/4, theta = -3pi/4: the raw error is
// 3pi/2, the wrapped one -pi/2, so the robot turns clockwise (the short way).
TEST(HeadingTracker, TurnsTheShortWay) {
  PidState s;
  const PidGains g{2.0, 0.0, 0.0, 1.0};
  const UnicycleCommand u = track_velocity(Vec2(-1, 1), -0.75 * kPi, 0.5, g, s, 0.01, false);
  EXPECT_NEAR(u.omega, -kPi, 1e-12);  // 2 * (-pi/2)
  EXPECT_NEAR(u.v, 0.5, 1e-12);       // |u| = sqrt 2 capped at 0.5
  PidState s2;
  const UnicycleCommand slow = track_velocity(Vec2(-1, 1), -0.75 * kPi, 0.5, g, s2, 0.01, true);
  EXPECT_NEAR(slow.v, 0.0, 1e-12);  // cos(-pi/2) = 0: turn first
}

// Eqs. 5.17-5.19: e = (3, 4), |e| = 5, v0 = 0.2, a = 1: K = 0.2 (1 - e^-25) / 5, u = K e.
TEST(GoToGoal, Eq5_19CappedGain) {
  const Vec2 u = go_to_goal_velocity(Vec2(1, 1), Vec2(4, 5), 0.2, 1.0);
  const double k = 0.2 * (1.0 - std::exp(-25.0)) / 5.0;
  EXPECT_NEAR(u.x(), 3.0 * k, 1e-15);
  EXPECT_NEAR(u.y(), 4.0 * k, 1e-15);
  EXPECT_NEAR(u.norm(), 0.2, 1e-9);  // far away: speed v0
  // Near the goal the speed falls smoothly: |e| = 0.1, a = 1 -> v0 (1 - e^-0.01) = 0.00199...
  EXPECT_NEAR(go_to_goal_velocity(Vec2(0, 0), Vec2(0.1, 0), 0.2, 1.0).norm(),
              0.2 * (1.0 - std::exp(-0.01)), 1e-15);
  EXPECT_EQ(go_to_goal_velocity(Vec2(1, 1), Vec2(1, 1), 0.2, 1.0), Vec2(0, 0));
}

// Eq. 5.20: one obstacle point at (1, 0), robot at (0, 0): move straight away, at speed v0.
TEST(AvoidObstacle, Eq5_20PointsAway) {
  const std::vector<Vec2> pts{Vec2(1, 0)};
  const Vec2 u = avoid_obstacle_velocity(Vec2(0, 0), pts, 0.3);
  EXPECT_NEAR(u.x(), -0.3, 1e-15);
  EXPECT_NEAR(u.y(), 0.0, 1e-15);
  // Two points, the nearer one weighs more: (0, 1) at distance 1 and (2, 0) at distance 2.
  // unit away-vectors weighted 1/(1 + 1e-3) and 1/(4 + 1e-3): the sum leans mostly to -y.
  const std::vector<Vec2> two{Vec2(0, 1), Vec2(2, 0)};
  const Vec2 v = avoid_obstacle_velocity(Vec2(0, 0), two, 1.0);
  const double wy = 1.0 / (1.0 + 1e-3), wx = 1.0 / (4.0 + 1e-3);
  EXPECT_NEAR(v.y() / v.x(), wy / wx, 1e-9);
  EXPECT_EQ(avoid_obstacle_velocity(Vec2(0, 0), {}, 1.0), Vec2(0, 0));
}

// Eq. 5.21: sigma_1 + sigma_2 = 1.
TEST(Blending, Eq5_21) {
  const Vec2 u = blend_velocities(Vec2(1, 0), Vec2(0, 1), 0.25);
  EXPECT_DOUBLE_EQ(u.x(), 0.75);
  EXPECT_DOUBLE_EQ(u.y(), 0.25);
  EXPECT_DOUBLE_EQ(blend_weight(0.01, 0.03, 0.15), 1.0);
  EXPECT_DOUBLE_EQ(blend_weight(0.2, 0.03, 0.15), 0.0);
  EXPECT_DOUBLE_EQ(blend_weight(0.09, 0.03, 0.15), 0.5);  // the middle of the smoothstep
}

// Eqs. 5.22-5.24: wall below the robot, u_AO = (0, 1). Clockwise R(-pi/2) u_AO = (1, 0):
// moving right with the obstacle on the right. Goal to the right: clockwise is chosen.
TEST(FollowBoundary, Eq5_22To5_24Direction) {
  const Vec2 u_ao(0, 1);
  EXPECT_EQ(follow_boundary_tangent(u_ao, Turn::Clockwise), Vec2(1, 0));
  EXPECT_EQ(follow_boundary_tangent(u_ao, Turn::CounterClockwise), Vec2(-1, 0));
  EXPECT_EQ(choose_turn(Vec2(1, -0.5), u_ao), Turn::Clockwise);
  EXPECT_EQ(choose_turn(Vec2(-1, -0.5), u_ao), Turn::CounterClockwise);
}

TEST(FollowBoundary, HoldsItsDistance) {
  const Vec2 away(0, 1);
  // At the standoff distance: pure tangent.
  Vec2 u = follow_boundary_velocity(away, 0.08, Turn::Clockwise, 0.08, 10.0, 0.1);
  EXPECT_NEAR(u.x(), 0.1, 1e-15);
  EXPECT_NEAR(u.y(), 0.0, 1e-15);
  // Too close (0.03 < 0.08): correction 10 * 0.05 = 0.5 outwards: direction (1, 0.5).
  u = follow_boundary_velocity(away, 0.03, Turn::Clockwise, 0.08, 10.0, 0.1);
  EXPECT_NEAR(u.y() / u.x(), 0.5, 1e-12);
  EXPECT_NEAR(u.norm(), 0.1, 1e-15);
  // Too far: leans in.
  u = follow_boundary_velocity(away, 0.13, Turn::Clockwise, 0.08, 10.0, 0.1);
  EXPECT_LT(u.y(), 0.0);
}
