// The guards and resets of Fig 5.11 and Fig 5.7, each on values worked by hand (QuickBot
// defaults: d_unsafe 0.03, hysteresis 0.02, d_fb 0.08, d_o 0.12, epsilon 0.05, delta 0.02 m).
#include <gtest/gtest.h>

#include "floornav/nav/supervisor_guards.hpp"

using namespace floornav;

namespace {
// The robot at the origin heading for (1, 0); an obstacle point ahead and a little to the left,
// so u_AO points back and right: u_AO = (-1, -0.2) (only directions matter to the guards).
NavigationInput blocked_ahead(double clearance) {
  NavigationInput in;
  in.goal = Vec2(1.0, 0.0);
  in.goal_distance = 1.0;
  in.u_gtg = Vec2(1.0, 0.0);
  in.u_ao = Vec2(-1.0, -0.2);
  in.away = in.u_ao.normalized();
  in.clearance = clearance;
  in.obstacle_sensed = true;
  return in;
}
}  // namespace

TEST(SupervisorGuards, AtGoalIsStrictlyInsideEpsilon) {
  const NavigationParams p;  // epsilon 0.05
  NavigationInput in;
  in.goal_distance = 0.049;
  EXPECT_TRUE(guards::at_goal(in, p));
  in.goal_distance = 0.05;
  EXPECT_FALSE(guards::at_goal(in, p));
}

TEST(SupervisorGuards, AvoidObstacleIsAFatGuard) {
  const NavigationParams p;  // enter AO below 0.03, leave it at 0.03 + 0.02
  EXPECT_TRUE(guards::too_close(blocked_ahead(0.029), p));
  EXPECT_FALSE(guards::too_close(blocked_ahead(0.03), p));
  EXPECT_FALSE(guards::safe_again(blocked_ahead(0.049), p));
  EXPECT_TRUE(guards::safe_again(blocked_ahead(0.05), p));
}

TEST(SupervisorGuards, ClearShotIsEq5_27) {
  const NavigationParams p;
  NavigationInput in = blocked_ahead(0.1);
  EXPECT_FALSE(guards::clear_shot(in, p));  // <(-1, -0.2), (1, 0)> = -1
  in.u_ao = Vec2(0.1, 1.0);                 // the obstacle is behind and to the right
  EXPECT_TRUE(guards::clear_shot(in, p));   // <(0.1, 1), (1, 0)> = 0.1 > 0
  NavigationParams corridor = p;
  corridor.clear_shot_corridor = 0.5;
  in.corridor_blocked = true;
  EXPECT_FALSE(guards::clear_shot(in, corridor));  // the extension asks the corridor instead
}

TEST(SupervisorGuards, ObstacleAheadTurnsByEqs5_23And5_24) {
  const NavigationParams p;  // d_o 0.12
  // u_FB^c = R(-pi/2) u_AO = (u_AO.y, -u_AO.x) = (-0.2, 1): <(1, 0), (-0.2, 1)> = -0.2 < 0, so
  // clockwise heads away from the goal and eq. 5.24 picks counter-clockwise.
  EXPECT_TRUE(guards::obstacle_ahead(blocked_ahead(0.11), p, Turn::CounterClockwise));
  EXPECT_FALSE(guards::obstacle_ahead(blocked_ahead(0.11), p, Turn::Clockwise));
  // Not yet met (at d_o exactly), or met but with a clear shot: keep going to the goal.
  EXPECT_FALSE(guards::obstacle_ahead(blocked_ahead(0.12), p, Turn::CounterClockwise));
  NavigationInput beside = blocked_ahead(0.11);
  beside.u_ao = Vec2(0.1, -1.0);  // a wall beside the path: <u_AO, u_GTG> = 0.1 > 0
  EXPECT_FALSE(guards::obstacle_ahead(beside, p, Turn::CounterClockwise));
  EXPECT_FALSE(guards::obstacle_ahead(beside, p, Turn::Clockwise));
}

TEST(SupervisorGuards, FollowBoundaryResetStoresDTau) {
  NavigationMemory m;
  NavigationInput in = blocked_ahead(0.1);
  in.goal_distance = 2.5;
  resets::start_following(in, m, Turn::CounterClockwise);
  EXPECT_EQ(m.d_tau, 2.5);
  EXPECT_EQ(m.turn, Turn::CounterClockwise);
  EXPECT_TRUE(m.following);
  resets::stop_following(m);
  EXPECT_FALSE(m.following);
}

TEST(SupervisorGuards, ProgressNeedsDeltaBelowDTauAndAClearShot) {
  const NavigationParams p;  // delta 0.02
  NavigationMemory m;
  m.d_tau = 1.0;
  NavigationInput in = blocked_ahead(0.1);
  in.u_ao = Vec2(0.1, 1.0);  // clear shot
  in.goal_distance = 0.97;   // 0.97 < 1.0 - 0.02
  EXPECT_TRUE(guards::progress_and_clear_shot(in, m, p));
  in.goal_distance = 0.99;  // closer than d_tau, but not by delta
  EXPECT_FALSE(guards::progress_and_clear_shot(in, m, p));
  in.goal_distance = 0.5;
  in.u_ao = Vec2(-1.0, 0.0);  // progress, but the obstacle is still in the way
  EXPECT_FALSE(guards::progress_and_clear_shot(in, m, p));
}

TEST(SupervisorGuards, AvoidObstacleResumesTheEpisodesDirection) {
  const NavigationParams p;
  NavigationMemory m;
  m.following = true;
  m.turn = Turn::Clockwise;
  m.d_tau = 3.0;
  const NavigationInput safe = blocked_ahead(0.05);
  EXPECT_TRUE(guards::resumes_following(safe, m, p, Turn::Clockwise));
  EXPECT_FALSE(guards::resumes_following(safe, m, p, Turn::CounterClockwise));
  EXPECT_FALSE(guards::resumes_following(blocked_ahead(0.04), m, p, Turn::Clockwise));
  resets::resume_following(safe, m, Turn::Clockwise);
  EXPECT_EQ(m.d_tau, 3.0);  // the episode goes on: d_tau is kept
  // A fresh episode (AO entered from GTG) picks eq. 5.24's direction and stores d_tau.
  NavigationMemory fresh;
  EXPECT_TRUE(guards::resumes_following(safe, fresh, p, Turn::CounterClockwise));
  resets::resume_following(safe, fresh, Turn::CounterClockwise);
  EXPECT_EQ(fresh.d_tau, 1.0);
}

TEST(SupervisorGuards, HardSwitchingSwitchesAtDO) {
  const NavigationParams p;  // d_o 0.12
  EXPECT_TRUE(guards::within_d_o(blocked_ahead(0.119), p));
  EXPECT_FALSE(guards::beyond_d_o(blocked_ahead(0.119), p));
  EXPECT_TRUE(guards::beyond_d_o(blocked_ahead(0.12), p));
}
