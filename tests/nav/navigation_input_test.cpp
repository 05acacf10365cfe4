// make_navigation_input for a disc body (one pass over the points: the obstacle_range filter,
// u_AO and the clearance), against the same steps written out one after the other, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/nav/behaviours.hpp"
#include "floornav/nav/navigation_input.hpp"
#include "support/bits.hpp"

namespace floornav {
namespace {

using test::bits;

// The steps one after the other: the points within obstacle_range + body_radius (the first 1024
// of them), then eq. 5.20 over those, then the nearest of them from the body disc.
NavigationInput reference(const Vec2& x, const Vec2& goal, const std::vector<Vec2>& points,
                          double body_radius, const NavigationParams& p) {
  NavigationInput in;
  in.x = x;
  in.goal = goal;
  in.goal_distance = (goal - x).norm();
  in.u_gtg = go_to_goal_velocity(x, goal, p.v0, p.gtg_a);
  if (p.clear_shot_corridor > 0.0)
    in.corridor_blocked =
        !corridor_clear(x, goal, points, p.clear_shot_corridor, body_radius + p.d_unsafe);
  std::vector<Vec2> near;
  const double limit = p.obstacle_range + body_radius;
  for (const Vec2& q : points)
    if (p.obstacle_range <= 0.0 || ((q - x).squaredNorm() <= limit * limit && near.size() < 1024))
      near.push_back(q);
  in.u_ao = avoid_obstacle_velocity(x, near, p.v0);
  in.away = normalized_or_zero(in.u_ao);
  for (const Vec2& q : near) {
    in.clearance = std::min(in.clearance, (q - x).norm() - body_radius);
    in.obstacle_sensed = true;
  }
  return in;
}

void expect_same(const NavigationInput& a, const NavigationInput& b) {
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(bits(a.u_gtg[k]), bits(b.u_gtg[k]));
    EXPECT_EQ(bits(a.u_ao[k]), bits(b.u_ao[k]));
    EXPECT_EQ(bits(a.away[k]), bits(b.away[k]));
  }
  EXPECT_EQ(bits(a.clearance), bits(b.clearance));
  EXPECT_EQ(bits(a.goal_distance), bits(b.goal_distance));
  EXPECT_EQ(a.obstacle_sensed, b.obstacle_sensed);
  EXPECT_EQ(a.corridor_blocked, b.corridor_blocked);
}

TEST(NavigationInput, DiscBodyHandWorked) {
  NavigationParams p;
  p.v0 = 0.5;
  p.obstacle_range = 1.0;
  // A point 0.5 m ahead, one on the robot itself (no direction: it adds nothing to u_AO), one
  // 3 m away (beyond obstacle_range + body radius: it neither pushes nor counts).
  const std::vector<Vec2> points{{0.5, 0.0}, {0.0, 0.0}, {3.0, 0.0}};
  const NavigationInput in = make_navigation_input(Vec2(0, 0), Vec2(5, 0), points, 0.2, p);
  EXPECT_EQ(in.u_ao, Vec2(-0.5, 0.0));
  EXPECT_EQ(in.away, Vec2(-1.0, 0.0));
  EXPECT_EQ(in.clearance, -0.2);  // the point on the robot: 0 - 0.2
  EXPECT_TRUE(in.obstacle_sensed);
  // Only the far point: nothing sensed, no push, infinite clearance.
  const std::vector<Vec2> far{{3.0, 0.0}};
  const NavigationInput none = make_navigation_input(Vec2(0, 0), Vec2(5, 0), far, 0.2, p);
  EXPECT_FALSE(none.obstacle_sensed);
  EXPECT_EQ(none.u_ao, Vec2::Zero());
  EXPECT_EQ(none.clearance, std::numeric_limits<double>::infinity());
  // Without obstacle_range every point counts, the far one too.
  p.obstacle_range = 0.0;
  const NavigationInput all = make_navigation_input(Vec2(0, 0), Vec2(5, 0), far, 0.2, p);
  EXPECT_TRUE(all.obstacle_sensed);
  EXPECT_EQ(all.clearance, 3.0 - 0.2);
  EXPECT_EQ(all.u_ao, Vec2(-0.5, 0.0));
}

TEST(NavigationInput, DiscBodyMatchesTheStepsOneAfterTheOther) {
  Rng rng(9);
  for (int i = 0; i < 400; ++i) {
    NavigationParams p;
    p.v0 = rng.uniform(0.1, 1.0);
    p.obstacle_range = i % 3 == 0 ? 0.0 : rng.uniform(0.3, 2.0);
    p.clear_shot_corridor = i % 4 == 0 ? 1.0 : 0.0;
    const Vec2 x(rng.uniform(-5, 5), rng.uniform(-5, 5));
    const Vec2 goal(rng.uniform(-5, 5), rng.uniform(-5, 5));
    // Some clouds with more near points than the filter keeps (1024).
    const int n = i % 10 == 0 ? 1500 : static_cast<int>(rng.uniform(0.0, 200.0));
    const double spread = i % 10 == 0 ? 0.5 : 4.0;
    std::vector<Vec2> points;
    for (int k = 0; k < n; ++k)
      points.push_back(x + Vec2(rng.uniform(-spread, spread), rng.uniform(-spread, spread)));
    if (n > 0 && i % 7 == 0) points[0] = x;  // a point on the robot
    const double body = rng.uniform(0.05, 0.4);
    SCOPED_TRACE(i);
    expect_same(make_navigation_input(x, goal, points, body, p),
                reference(x, goal, points, body, p));
  }
}

}  // namespace
}  // namespace floornav
