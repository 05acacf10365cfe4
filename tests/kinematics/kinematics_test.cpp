#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "floornav/geometry/angle.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/kinematics/unicycle.hpp"
#include "support/bits.hpp"

using namespace floornav;

namespace {
// The QuickBot: R = 0.0325 m, L = 0.09925 m.
const DiffDriveParams kQuickBot{0.0325, 0.09925, 13.61, 0.0};
}  // namespace

// Eqs. 5.5-5.8 worked by hand: w_r = 10, w_l = 6 rad/s.
// V = 0.0325 (10 + 6) / 2 = 0.26 m/s; omega = 0.0325 (10 - 6) / 0.09925 = 1.309823... rad/s.
TEST(DifferentialDrive, Eq5_5To5_8WheelsToUnicycle) {
  const UnicycleCommand u = wheels_to_unicycle(kQuickBot, {6.0, 10.0});
  EXPECT_NEAR(u.v, 0.26, 1e-15);
  EXPECT_NEAR(u.omega, 0.13 / 0.09925, 1e-14);
  EXPECT_NEAR(u.omega, 1.3098236776, 1e-9);
}

// Eqs. 5.10/5.11 by hand: V = 0.2 m/s, omega = 1 rad/s.
// w_r = (0.4 + 0.09925) / 0.065 = 7.680769..., w_l = (0.4 - 0.09925) / 0.065 = 4.626923...
TEST(DifferentialDrive, Eq5_10_5_11UnicycleToWheels) {
  const WheelSpeeds w = unicycle_to_wheels(kQuickBot, {0.2, 1.0});
  EXPECT_NEAR(w.right, 7.6807692308, 1e-9);
  EXPECT_NEAR(w.left, 4.6269230769, 1e-9);
}

TEST(DifferentialDrive, MappingRoundTrips) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> v(-0.4, 0.4), om(-5.0, 5.0);
  for (int i = 0; i < 1000; ++i) {
    const UnicycleCommand u{v(rng), om(rng)};
    const UnicycleCommand back = wheels_to_unicycle(kQuickBot, unicycle_to_wheels(kQuickBot, u));
    EXPECT_NEAR(back.v, u.v, 1e-12);
    EXPECT_NEAR(back.omega, u.omega, 1e-12);
  }
}

// Saturation keeps omega and gives up speed: V = 0.44 m/s with omega = 2 rad/s asks
// w_r = (0.88 + 0.1985)/0.065 = 16.59 > 13.61. Both wheels shift down by 2.98, so omega stays 2.
TEST(DifferentialDrive, SaturationKeepsOmegaGivesUpSpeed) {
  const WheelSpeeds w = saturate_wheels(kQuickBot, {0.44, 2.0});
  EXPECT_NEAR(w.right, 13.61, 1e-12);
  const UnicycleCommand u = wheels_to_unicycle(kQuickBot, w);
  EXPECT_NEAR(u.omega, 2.0, 1e-12);
  EXPECT_LT(u.v, 0.44);
  // V = 13.61*0.0325 - 2*0.09925/2 = 0.442325 - 0.09925 = 0.343075
  EXPECT_NEAR(u.v, 0.343075, 1e-9);
}

TEST(DifferentialDrive, SaturationNeverFlipsTheTurn) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> v(-2.0, 2.0), om(-40.0, 40.0);
  for (int i = 0; i < 2000; ++i) {
    const UnicycleCommand want{v(rng), om(rng)};
    const WheelSpeeds w = saturate_wheels(kQuickBot, want);
    EXPECT_LE(std::abs(w.left), kQuickBot.max_wheel_speed + 1e-12);
    EXPECT_LE(std::abs(w.right), kQuickBot.max_wheel_speed + 1e-12);
    const UnicycleCommand got = wheels_to_unicycle(kQuickBot, w);
    if (std::abs(want.omega) > 1e-9) {
      EXPECT_GT(got.omega * want.omega, 0.0) << "turn flipped";
      // omega is clipped only to the turn-on-the-spot limit.
      EXPECT_NEAR(std::abs(got.omega), std::min(std::abs(want.omega), max_turn_rate(kQuickBot)),
                  1e-9);
    }
    EXPECT_LE(std::abs(got.v), std::abs(want.v) + 1e-12);  // speed only ever given up
  }
}

TEST(DifferentialDrive, MinimumWheelSpeedStalls) {
  DiffDriveParams p = kQuickBot;
  p.min_wheel_speed = 1.0;
  const WheelSpeeds w = saturate_wheels(p, {0.01, 0.0});  // 0.01/0.0325 = 0.31 rad/s
  EXPECT_EQ(w.left, 0.0);
  EXPECT_EQ(w.right, 0.0);
}

// Eqs. 5.7-5.9 integrated exactly. Straight: 0.5 m/s for 2 s along +y from the origin.
TEST(Unicycle, StraightLine) {
  const Pose2 p = integrate_unicycle({Vec2(0, 0), kPi / 2}, {0.5, 0.0}, 2.0);
  EXPECT_NEAR(p.position.x(), 0.0, 1e-15);
  EXPECT_NEAR(p.position.y(), 1.0, 1e-15);
}

// A quarter circle: V = pi/2 m/s, omega = pi/2 rad/s for 1 s is radius 1, from (0,0) facing +x
// to (1, 1) facing +y. Euler would miss this by centimetres; the arc is exact.
TEST(Unicycle, ExactArcQuarterCircle) {
  const Pose2 p = integrate_unicycle({Vec2(0, 0), 0.0}, {kPi / 2, kPi / 2}, 1.0);
  EXPECT_NEAR(p.position.x(), 1.0, 1e-12);
  EXPECT_NEAR(p.position.y(), 1.0, 1e-12);
  EXPECT_NEAR(p.theta, kPi / 2, 1e-12);
}

TEST(Unicycle, SmallStepsAgreeWithOneBigArc) {
  Pose2 p{Vec2(0.3, -0.2), 0.4};
  const UnicycleCommand u{0.3, -0.8};
  Pose2 q = p;
  for (int i = 0; i < 1000; ++i) q = integrate_unicycle(q, u, 0.005);
  const Pose2 big = integrate_unicycle(p, u, 5.0);
  EXPECT_NEAR(q.position.x(), big.position.x(), 1e-9);
  EXPECT_NEAR(q.position.y(), big.position.y(), 1e-9);
  EXPECT_NEAR(wrap_angle(q.theta - big.theta), 0.0, 1e-9);
}

// The caller's cosine and sine of the heading give the same pose, bit for bit.
TEST(Unicycle, AGivenHeadingGivesTheSamePoseBits) {
  for (double theta : {0.0, -0.0, 0.4, -3.0, kPi}) {
    const Pose2 p{Vec2(0.3, -0.2), theta};
    for (const UnicycleCommand u : {UnicycleCommand{0.3, -0.8}, UnicycleCommand{0.2, 0.0}}) {
      const Pose2 a = integrate_unicycle(p, u, 0.05);
      const Pose2 b = integrate_unicycle(p, u, 0.05, Vec2(std::cos(theta), std::sin(theta)));
      EXPECT_EQ(test::bits(a.position.x()), test::bits(b.position.x()));
      EXPECT_EQ(test::bits(a.position.y()), test::bits(b.position.y()));
      EXPECT_EQ(test::bits(a.theta), test::bits(b.theta));
    }
  }
}

TEST(Unicycle, TurnOnTheSpot) {
  const Pose2 p = integrate_unicycle({Vec2(1, 2), 0.0}, {0.0, 1.0}, 0.5);
  EXPECT_EQ(p.position, Vec2(1, 2));
  EXPECT_NEAR(p.theta, 0.5, 1e-15);
}
