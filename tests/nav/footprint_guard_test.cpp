// The footprint guard (nav/footprint_guard.hpp): the time at which the swept footprint meets a
// point, worked by hand for a straight drive and for turns on the spot, and what the guard makes
// of a command that would touch: slower on the same arc, or a way out, never a corner into a
// point.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "floornav/nav/footprint_guard.hpp"

using namespace floornav;

namespace {
// A 0.5 x 0.4 m rectangle (the Jackal's is 0.508 x 0.430): corners at sqrt(0.25^2 + 0.2^2) =
// 0.3202 m from the centre.
const std::vector<Vec2> kBox{{-0.25, -0.2}, {0.25, -0.2}, {0.25, 0.2}, {-0.25, 0.2}};
constexpr double kInf = std::numeric_limits<double>::infinity();

// The point (0.27, 0.05) in the robot frame: 0.02 m ahead of the front edge, beside the front-left
// corner, at r = 0.274591 m (polar angle phi0 = atan2(0.05, 0.27) = 0.182964 rad), inside the
// circle the corners sweep. Seen from the robot, a turn by theta moves it to polar angle
// phi0 - theta; it crosses the front edge x = 0.25 where cos(phi) = 0.25 / r, phi = +-0.428357
// (|y| = r sin(phi) = 0.1140 < 0.2: on the edge). Clockwise (theta < 0) it gets there after
// 0.428357 - 0.182964 = 0.245393 rad, counter-clockwise after 0.182964 + 0.428357 = 0.611321 rad.
const std::vector<Vec2> kBesideCorner{{0.27, 0.05}};
}  // namespace

TEST(FootprintGuard, StraightDriveMeetsAPointAheadWhenTheGapFallsBelowTheMargin) {
  // Point 1 m ahead, front edge at 0.25 m: the gap 0.75 - t falls below 0.04 after t = 0.71 s at
  // 1 m/s; samples every 0.02 m of travel (0.02 s) see it at the first sample after: 0.72 s.
  const std::vector<Vec2> ahead{{1.0, 0.0}};
  const double t = time_to_contact(kBox, ahead, 1.0, 0.0, 1.0, 0.04);
  EXPECT_GT(t, 0.71);
  EXPECT_NEAR(t, 0.72, 1e-9);
  // Twice as fast, twice as soon (to within one sample).
  EXPECT_NEAR(time_to_contact(kBox, ahead, 2.0, 0.0, 1.0, 0.04, 0.002), 0.355, 0.002);
  // Backing away, or a horizon too short to get there: never.
  EXPECT_EQ(time_to_contact(kBox, ahead, -1.0, 0.0, 1.0, 0.04), kInf);
  EXPECT_EQ(time_to_contact(kBox, ahead, 1.0, 0.0, 0.7, 0.04), kInf);
}

TEST(FootprintGuard, APointBesideTheWayIsNotMet) {
  // Ahead and 0.1 m to the left of the left edge (y = 0.2): a straight drive passes it 0.1 m
  // away, more than the margin.
  const std::vector<Vec2> beside{{0.5, 0.3}};
  EXPECT_NEAR(footprint_clearance(kBox, beside), std::hypot(0.25, 0.1), 1e-12);
  EXPECT_EQ(time_to_contact(kBox, beside, 1.0, 0.0, 1.0, 0.04), kInf);
  // With a margin of 0.2 m it is met once the gap hypot(0.25 - t, 0.1) is below 0.2:
  // t > 0.25 - sqrt(0.03) = 0.076795 s.
  EXPECT_NEAR(time_to_contact(kBox, beside, 1.0, 0.0, 1.0, 0.2, 0.002), 0.076795, 0.002);
  // Abreast of the left edge: 0.1 m now, within a margin of 0.2 m at once.
  const std::vector<Vec2> abreast{{0.0, 0.3}};
  EXPECT_NEAR(footprint_clearance(kBox, abreast), 0.1, 1e-12);
  EXPECT_EQ(time_to_contact(kBox, abreast, 1.0, 0.0, 1.0, 0.2), 0.0);
}

TEST(FootprintGuard, TurningOnTheSpotSwingsACornerIntoAPointBesideIt) {
  // Not in contact now (0.02 m from the front edge), but both turns on the spot reach it: the
  // corners sweep a circle of 0.3202 m and the point is at 0.2746 m. Fine samples (2 mm).
  EXPECT_NEAR(footprint_clearance(kBox, kBesideCorner), 0.02, 1e-12);
  EXPECT_NEAR(time_to_contact(kBox, kBesideCorner, 0.0, -1.0, 2.0, 0.0, 0.002), 0.245393, 0.007);
  EXPECT_NEAR(time_to_contact(kBox, kBesideCorner, 0.0, 1.0, 2.0, 0.0, 0.002), 0.611321, 0.007);
  // At 2 rad/s, half the time.
  EXPECT_NEAR(time_to_contact(kBox, kBesideCorner, 0.0, -2.0, 2.0, 0.0, 0.002), 0.122697, 0.004);
  // A point outside the corners' circle is never met by a turn on the spot.
  const std::vector<Vec2> outside{{0.33, 0.0}};
  EXPECT_EQ(time_to_contact(kBox, outside, 0.0, 3.0, 3.0, 0.0), kInf);
}

TEST(FootprintGuard, WantedCommandFreeOverTheHorizonIsUntouched) {
  FootprintGuard guard(kBox, {.horizon = 0.5, .margin = 0.02});
  const std::vector<Vec2> far{{3.0, 0.0}};
  guard.set_points(Pose2{Vec2::Zero(), 0.0}, far, 2.0);
  const GuardResult r = guard.check(1.0, 0.3);
  EXPECT_EQ(r.v, 1.0);
  EXPECT_EQ(r.omega, 0.3);
  EXPECT_EQ(r.scale, 1.0);
  EXPECT_FALSE(r.replaced);
}

TEST(FootprintGuard, PointsAreTakenIntoTheRobotFrame) {
  // The robot at (1, 2) facing +y: a world point 1 m north of it is 1 m ahead.
  FootprintGuard guard(kBox, {.horizon = 1.0, .margin = 0.04});
  const std::vector<Vec2> north{{1.0, 3.0}};
  guard.set_points(Pose2{Vec2(1.0, 2.0), M_PI / 2}, north, 2.0);
  ASSERT_EQ(guard.local_points().size(), 1u);
  EXPECT_NEAR(guard.local_points()[0].x(), 1.0, 1e-12);
  EXPECT_NEAR(guard.local_points()[0].y(), 0.0, 1e-12);
  // Approach (Nav2's collision monitor): contact 0.72 s away, horizon 1 s -> 0.72 of the speed.
  const GuardResult r = guard.check(1.0, 0.0);
  EXPECT_NEAR(r.scale, 0.72, 1e-9);
  EXPECT_NEAR(r.v, 0.72, 1e-9);
  EXPECT_EQ(r.omega, 0.0);
  EXPECT_FALSE(r.replaced);
  // A point beyond the reach of any sweep within the horizon is not kept.
  const std::vector<Vec2> far{{1.0, 9.0}};
  guard.set_points(Pose2{Vec2(1.0, 2.0), M_PI / 2}, far, 2.0);
  EXPECT_TRUE(guard.local_points().empty());
}

TEST(FootprintGuard, ATurnThatWouldSwingACornerIntoAPointIsSlowedOrReplaced) {
  // Horizon 0.5 s at -1 rad/s: contact at 0.245 s -> scale 0.49 (>= min_scale 0.3): the same
  // turn, slower, so that contact stays 0.5 s away.
  FootprintGuard guard(kBox, {.horizon = 0.5, .margin = 0.0});
  guard.set_points(Pose2{}, kBesideCorner, 2.0);
  const GuardResult slow = guard.check(0.0, -1.0);
  EXPECT_FALSE(slow.replaced);
  // Sampled every 0.02 m of corner travel (0.0625 rad here): contact is seen at the first
  // sample at or after 0.245 s, never before.
  EXPECT_GE(slow.scale, 0.245393 / 0.5);
  EXPECT_LE(slow.scale, (0.245393 + 0.02 / 0.320156) / 0.5);
  EXPECT_EQ(slow.v, 0.0);
  EXPECT_LT(slow.omega, 0.0);
  EXPECT_GT(slow.omega, -0.62);

  // At -4 rad/s contact is 0.061 s away: scale 0.12 < 0.3, blocked. The guard must not turn the
  // corner into the point: what it chooses is freer than the wanted turn, and not the wanted
  // turn at all.
  const GuardResult out = guard.check(0.0, -4.0);
  EXPECT_TRUE(out.replaced);
  const double wanted_free = guard.free_fraction(0.0, -4.0);
  EXPECT_LT(wanted_free, 0.3);
  EXPECT_GT(guard.free_fraction(out.v, out.omega), wanted_free);
  EXPECT_FALSE(out.v == 0.0 && out.omega < 0.0) << "a clockwise turn on the spot hits the point";
}

TEST(FootprintGuard, AlreadyNearAPointItMayStillMoveAway) {
  // 0.01 m from the front edge, margin 0.02: backing away or standing still is allowed, driving
  // on is not.
  FootprintGuard guard(kBox, {.horizon = 0.5, .margin = 0.02});
  const std::vector<Vec2> close{{0.26, 0.0}};
  guard.set_points(Pose2{}, close, 2.0);
  EXPECT_NEAR(guard.clearance(), 0.01, 1e-12);
  const GuardResult back = guard.check(-0.3, 0.0);
  EXPECT_EQ(back.v, -0.3);
  EXPECT_FALSE(back.replaced);
  const GuardResult on = guard.check(0.5, 0.0);
  EXPECT_TRUE(on.replaced || on.v < 0.5);
  EXPECT_LE(on.v, 0.0) << "never further towards the point";
}
