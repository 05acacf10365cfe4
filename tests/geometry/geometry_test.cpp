#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/ray.hpp"
#include "floornav/geometry/segment.hpp"

using namespace floornav;

TEST(WrapAngle, Eq5_14WrapsIntoHalfOpenInterval) {
  // 3 pi/2 is the same direction as -pi/2.
  EXPECT_NEAR(wrap_angle(1.5 * kPi), -0.5 * kPi, 1e-12);
  EXPECT_NEAR(wrap_angle(-1.5 * kPi), 0.5 * kPi, 1e-12);
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);     // pi stays pi: (-pi, pi]
  EXPECT_NEAR(wrap_angle(-kPi), kPi, 1e-12);  // -pi becomes pi
  EXPECT_NEAR(wrap_angle(7.0), 7.0 - 2.0 * kPi, 1e-12);
}

TEST(WrapAngle, IsIdempotent) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> d(-50.0, 50.0);
  for (int i = 0; i < 1000; ++i) {
    const double a = wrap_angle(d(rng));
    EXPECT_EQ(wrap_angle(a), a);
    EXPECT_GT(a, -kPi);
    EXPECT_LE(a, kPi);
  }
}

// coarse_atan2's error stays below the 2e-6 rad it documents, in every octant, on the octant
// borders and at tiny lengths.
TEST(CoarseAtan2, StaysWithinTwoMicroradiansOfAtan2) {
  double worst = 0.0;
  for (int i = 0; i < 200000; ++i) {
    const double a = -kPi + 2.0 * kPi * (i + 0.5) / 200000.0;
    for (const double r : {1e-9, 1.0, 1e6}) {
      const double x = r * std::cos(a), y = r * std::sin(a);
      worst = std::max(worst, std::abs(wrap_angle(coarse_atan2(y, x) - std::atan2(y, x))));
    }
  }
  for (const double a : {0.0, 0.25 * kPi, 0.5 * kPi, 0.75 * kPi, kPi, -0.25 * kPi, -0.5 * kPi})
    worst = std::max(worst, std::abs(wrap_angle(coarse_atan2(std::sin(a), std::cos(a)) - a)));
  EXPECT_LT(worst, 2e-6);
  EXPECT_GT(worst, 1e-7);  // a polynomial, not atan2 itself: the margins are needed
}

TEST(Pose2, ComposeAndInverseRoundTrip) {
  const Pose2 a{Vec2(1.0, 2.0), 0.5};
  const Pose2 b{Vec2(-0.3, 0.7), -1.2};
  const Pose2 ab = a.compose(b);
  const Pose2 back = a.inverse().compose(ab);
  EXPECT_NEAR(back.position.x(), b.position.x(), 1e-12);
  EXPECT_NEAR(back.position.y(), b.position.y(), 1e-12);
  EXPECT_NEAR(back.theta, b.theta, 1e-12);
  // A sensor 1 m ahead of a robot facing +y sits at +1 in y.
  const Pose2 robot{Vec2(0, 0), kPi / 2};
  const Vec2 p = robot.transform_point(Vec2(1, 0));
  EXPECT_NEAR(p.x(), 0.0, 1e-15);
  EXPECT_NEAR(p.y(), 1.0, 1e-15);
}

TEST(Rotation, QuarterTurnsAreExact) {
  // R(-pi/2) (0, 1) = (1, 0): the clockwise rotation of eq. 5.22.
  EXPECT_EQ(rotate_cw90(Vec2(0, 1)), Vec2(1, 0));
  EXPECT_EQ(rotate_ccw90(Vec2(1, 0)), Vec2(0, 1));
  const Vec2 r = rotate(Vec2(1, 0), kPi / 2);
  EXPECT_NEAR(r.x(), 0.0, 1e-15);
  EXPECT_NEAR(r.y(), 1.0, 1e-15);
}

TEST(Segment, DistanceAndNearestPoint) {
  const Segment s{Vec2(0, 0), Vec2(2, 0)};
  EXPECT_DOUBLE_EQ(distance(s, Vec2(1, 1)), 1.0);
  EXPECT_DOUBLE_EQ(distance(s, Vec2(3, 0)), 1.0);   // beyond the end: to the endpoint
  EXPECT_DOUBLE_EQ(distance(s, Vec2(-3, 4)), 5.0);  // 3-4-5 to the start
  EXPECT_EQ(nearest_point(s, Vec2(0.5, -2)), Vec2(0.5, 0));
  const Segment degenerate{Vec2(1, 1), Vec2(1, 1)};
  EXPECT_DOUBLE_EQ(distance(degenerate, Vec2(4, 5)), 5.0);
}

TEST(Segment, RayIntersection) {
  const Segment wall{Vec2(2, -1), Vec2(2, 1)};
  auto t = intersect_ray(wall, Vec2(0, 0), Vec2(1, 0));
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(*t, 2.0);
  // 45 degrees: hits at (2, 2)? No: the wall ends at y = 1, so it misses.
  const double h = std::sqrt(0.5);
  EXPECT_FALSE(intersect_ray(wall, Vec2(0, 0), Vec2(h, h)));
  // From (0, 0.5) at 45 degrees: hits (2, 2.5)? misses; from (0,-1) it hits (2, 1) at 2 sqrt 2.
  t = intersect_ray(wall, Vec2(0, -1), Vec2(h, h));
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 2.0 * std::sqrt(2.0), 1e-12);
  EXPECT_FALSE(intersect_ray(wall, Vec2(0, 0), Vec2(-1, 0)));  // behind
  // Collinear: the nearer end.
  const Segment along{Vec2(3, 0), Vec2(5, 0)};
  t = intersect_ray(along, Vec2(0, 0), Vec2(1, 0));
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(*t, 3.0);
}

TEST(Ray, ClipToBoxNarrowsTheIntervalBySlabs) {
  const Box2 box{Vec2(1, 1), Vec2(3, 2)};
  const double h = std::sqrt(0.5);
  // From (0, 0) at 45 degrees: x in [1, 3] for t in [sqrt 2, 3 sqrt 2], y in [1, 2] for
  // t in [sqrt 2, 2 sqrt 2]: inside for t in [sqrt 2, 2 sqrt 2].
  double t0 = 0.0, t1 = 10.0;
  ASSERT_TRUE(clip_ray_to_box(Vec2(0, 0), Vec2(h, h), box, t0, t1));
  EXPECT_NEAR(t0, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(t1, 2.0 * std::sqrt(2.0), 1e-12);
  // The same ray cut short before the box, and pointing away from it: nothing left.
  t0 = 0.0, t1 = 1.0;
  EXPECT_FALSE(clip_ray_to_box(Vec2(0, 0), Vec2(h, h), box, t0, t1));
  t0 = 0.0, t1 = 10.0;
  EXPECT_FALSE(clip_ray_to_box(Vec2(0, 0), Vec2(-h, -h), box, t0, t1));
  // Parallel to x: inside the slab [1, 2) of y it keeps x's interval [1, 3]; on y = 2 (the
  // upper edge, as a cell's) and below y = 1 it misses.
  t0 = 0.0, t1 = 10.0;
  ASSERT_TRUE(clip_ray_to_box(Vec2(0, 1), Vec2(1, 0), box, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 1.0);
  EXPECT_DOUBLE_EQ(t1, 3.0);
  t0 = 0.0, t1 = 10.0;
  EXPECT_FALSE(clip_ray_to_box(Vec2(0, 2), Vec2(1, 0), box, t0, t1));
  t0 = 0.0, t1 = 10.0;
  EXPECT_FALSE(clip_ray_to_box(Vec2(0, 0.5), Vec2(1, 0), box, t0, t1));
}

TEST(Ray, SegmentHitKeepsTheNearerOfItAndBest) {
  const Vec2 a(2, -1), b(2, 1);
  const Vec2 e = b - a;
  // Straight at the wall 2 m ahead: 2 when best is farther, best when it is nearer.
  EXPECT_DOUBLE_EQ(ray_segment_hit(Vec2(0, 0), Vec2(1, 0), a, b, e, 5.0), 2.0);
  EXPECT_DOUBLE_EQ(ray_segment_hit(Vec2(0, 0), Vec2(1, 0), a, b, e, 1.5), 1.5);
  // Past the end (u > 1) and behind the origin: no hit.
  EXPECT_DOUBLE_EQ(ray_segment_hit(Vec2(0, 2), Vec2(1, 0), a, b, e, 5.0), 5.0);
  EXPECT_DOUBLE_EQ(ray_segment_hit(Vec2(3, 0), Vec2(1, 0), a, b, e, 5.0), 5.0);
  // Along the segment: its nearer end, or 0 from a point on it; beside the line: no hit.
  EXPECT_DOUBLE_EQ(ray_segment_hit(Vec2(2, -4), Vec2(0, 1), a, b, e, 5.0), 3.0);
  EXPECT_DOUBLE_EQ(ray_segment_hit(Vec2(2, 0), Vec2(0, 1), a, b, e, 5.0), 0.0);
  EXPECT_DOUBLE_EQ(ray_segment_hit(Vec2(2.5, -4), Vec2(0, 1), a, b, e, 5.0), 5.0);
  // A NaN direction counts as no hit (best), never NaN.
  const double nan = std::nan("");
  EXPECT_DOUBLE_EQ(ray_segment_hit(Vec2(0, 0), Vec2(nan, 0), a, b, e, 5.0), 5.0);
  // intersect_ray is the same test: the same bits, nullopt where ray_segment_hit gives best.
  const Vec2 o(0.3, -0.7), dir(std::cos(0.4), std::sin(0.4));
  EXPECT_EQ(*intersect_ray(Segment{a, b}, o, dir), ray_segment_hit(o, dir, a, b, e, 1e9));
}

TEST(Ray, ASegmentIsSeenFromItsSolidSideWhenTheOriginIsOnIt) {
  // a (2, -1) to b (2, 1) runs north: its left is west (x < 2), its right east.
  const Vec2 a(2, -1), e(0, 2);
  // From the origin (west): pa = (2, -1), cross(pa, e) = 2 * 2 - (-1) * 0 = 4 > 0.
  EXPECT_TRUE(seen_from_solid_side(+1.0, a - Vec2(0, 0), e));   // solid on the left (west)
  EXPECT_FALSE(seen_from_solid_side(-1.0, a - Vec2(0, 0), e));  // solid on the right (east)
  // From (3, 0) (east): pa = (-1, -1), cross = -1 * 2 - (-1) * 0 = -2 < 0.
  EXPECT_FALSE(seen_from_solid_side(+1.0, a - Vec2(3, 0), e));
  EXPECT_TRUE(seen_from_solid_side(-1.0, a - Vec2(3, 0), e));
  // On the line, or with no known side: from neither.
  EXPECT_FALSE(seen_from_solid_side(+1.0, a - Vec2(2, 5), e));
  EXPECT_FALSE(seen_from_solid_side(-1.0, a - Vec2(2, 5), e));
  EXPECT_FALSE(seen_from_solid_side(0.0, a - Vec2(0, 0), e));
}

TEST(Ray, CircleHitKeepsTheNearerOfItAndBest) {
  const Circle c{Vec2(3, 0), 1.0};
  EXPECT_DOUBLE_EQ(ray_circle_hit(Vec2(0, 0), Vec2(1, 0), c, 5.0), 2.0);
  EXPECT_DOUBLE_EQ(ray_circle_hit(Vec2(0, 0), Vec2(1, 0), c, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(ray_circle_hit(Vec2(0, 0), Vec2(0, 1), c, 5.0), 5.0);
}

TEST(Segment, Intersection) {
  EXPECT_TRUE(segments_intersect({Vec2(0, 0), Vec2(2, 2)}, {Vec2(0, 2), Vec2(2, 0)}));
  EXPECT_FALSE(segments_intersect({Vec2(0, 0), Vec2(1, 0)}, {Vec2(0, 1), Vec2(1, 1)}));
  EXPECT_TRUE(segments_intersect({Vec2(0, 0), Vec2(1, 0)}, {Vec2(1, 0), Vec2(1, 1)}));  // touch
}

TEST(Circle, RayAndDistance) {
  const Circle c{Vec2(3, 0), 1.0};
  auto t = intersect_ray(c, Vec2(0, 0), Vec2(1, 0));
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(*t, 2.0);
  EXPECT_FALSE(intersect_ray(c, Vec2(0, 0), Vec2(0, 1)));
  EXPECT_DOUBLE_EQ(*intersect_ray(c, Vec2(3, 0.5), Vec2(0, 1)), 0.0);  // inside
  EXPECT_DOUBLE_EQ(*intersect_ray(c, Vec2(0, 1), Vec2(1, 0)), 3.0);    // grazing: tangent at (3, 1)
  EXPECT_FALSE(intersect_ray(c, Vec2(5, 0), Vec2(1, 0)));              // behind
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(intersect_ray(c, Vec2(nan, 0), Vec2(1, 0)));  // no number, no hit
  EXPECT_DOUBLE_EQ(signed_distance(c, Vec2(0, 4)), 4.0);     // |(-3,4)| - 1
  EXPECT_DOUBLE_EQ(signed_distance(c, Vec2(3, 0)), -1.0);
}

TEST(Polygon, AreaAndWinding) {
  const std::vector<Vec2> ccw{{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  EXPECT_DOUBLE_EQ(signed_area(ccw), 2.0);
  const std::vector<Vec2> cw(ccw.rbegin(), ccw.rend());
  EXPECT_DOUBLE_EQ(signed_area(cw), -2.0);
}

// Practice problem 1: classify shapes as convex or concave, either winding.
TEST(Polygon, ConvexityPractice1) {
  const std::vector<Vec2> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  const std::vector<Vec2> square_cw{{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  const std::vector<Vec2> triangle{{0, 0}, {2, 0}, {1, 3}};
  const std::vector<Vec2> l_shape{{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const std::vector<Vec2> u_shape{{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const std::vector<Vec2> star{{0, 3},    {1, 1},     {3, 1},       {1.5, -0.5}, {2.5, -3},
                               {0, -1.5}, {-2.5, -3}, {-1.5, -0.5}, {-3, 1},     {-1, 1}};
  const std::vector<Vec2> pentagram{
      {0, 1}, {0.588, -0.809}, {-0.951, 0.309}, {0.951, 0.309}, {-0.588, -0.809}};
  EXPECT_TRUE(is_convex(square));
  EXPECT_TRUE(is_convex(square_cw));
  EXPECT_TRUE(is_convex(triangle));
  EXPECT_FALSE(is_convex(l_shape));
  EXPECT_FALSE(is_convex(u_shape));
  EXPECT_FALSE(is_convex(star));
  EXPECT_FALSE(is_convex(pentagram));  // turns all agree, but it winds twice
  EXPECT_FALSE(is_simple(pentagram));
  EXPECT_TRUE(is_simple(u_shape));
}

TEST(Polygon, ContainsConcave) {
  const std::vector<Vec2> u_shape{{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  EXPECT_TRUE(contains(u_shape, Vec2(0.5, 1.5)));   // left arm
  EXPECT_FALSE(contains(u_shape, Vec2(1.5, 1.5)));  // the pocket
  EXPECT_TRUE(contains(u_shape, Vec2(1.5, 0.5)));   // base
  EXPECT_TRUE(contains(u_shape, Vec2(3, 1)));       // on the boundary
  EXPECT_FALSE(contains(u_shape, Vec2(4, 1)));
  EXPECT_DOUBLE_EQ(boundary_distance(u_shape, Vec2(1.5, 1.5)), 0.5);
}

TEST(Polygon, Rectangle) {
  const auto r = make_rectangle(Vec2(1, 1), Vec2(2, 1), kPi / 2);
  EXPECT_NEAR(std::abs(signed_area(r)), 2.0, 1e-12);
  EXPECT_TRUE(contains(r, Vec2(1, 1.9)));  // rotated: 1 wide in x, 2 tall in y
  EXPECT_FALSE(contains(r, Vec2(1.9, 1)));
}
