// SensorLayout (a sensor list's lidars and fans, found once): what it finds in lists worked by
// hand, and compute_sensor_beams / sense_ranges with it against the plain functions that look
// for the runs at every call, bit for bit (beams, ranges and the noise draws).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sensing/sensor_fans.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"
#include "support/bits.hpp"

namespace floornav {
namespace {

using test::bits;

void append(std::vector<RangeSensorSpec>& to, const std::vector<RangeSensorSpec>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

RangeSensorSpec single(Vec2 at, double theta, double max_range) {
  return {{at, theta}, 0.02, max_range, 0.0, 1};
}

RangeSensorSpec cone(Vec2 at, double theta) {
  return {{at, theta}, 0.02, 0.5, 0.3, 5};
}

// The sensor lists the layout must agree on.
std::vector<std::vector<RangeSensorSpec>> sensor_lists() {
  std::vector<std::vector<RangeSensorSpec>> lists;
  // One lidar (the cave's Pioneer: 180 beams over 180 degrees, 8 m).
  lists.push_back(make_lidar(180, kPi, 0.0, 8.0, {Vec2(0.13, 0.0), 0.0}));
  // Two lidars, back to back on two mount points, and a full circle.
  {
    auto l = make_lidar(90, deg_to_rad(270.0), 0.05, 5.0, {Vec2(0.2, 0.1), 0.4});
    append(l, make_lidar(360, 2.0 * kPi, 0.1, 3.5, {Vec2(-0.2, -0.1), -2.9}));
    lists.push_back(l);
  }
  // Mixed: sonar cones, a lidar, a single beam on the lidar's mount point with its range (one
  // fan with it), a second lidar turning clockwise, an IR ring of singles.
  {
    std::vector<RangeSensorSpec> l;
    for (int k = 0; k < 8; ++k) l.push_back(cone(Vec2(0.1, 0.0), k * kPi / 4.0));
    append(l, make_lidar(40, deg_to_rad(240.0), 0.1, 4.0, {Vec2(0.1, 0.0), 0.0}));
    l.push_back(single(Vec2(0.1, 0.0), 3.0, 4.0));
    auto cw = make_lidar(33, kPi / 2.0, 0.02, 6.0, {Vec2(0.0, 0.05), 1.0});
    std::reverse(cw.begin(), cw.end());
    append(l, cw);
    for (int k = 0; k < 12; ++k) l.push_back(single(Vec2(0.15, 0.0), k * kPi / 6.0, 0.3));
    lists.push_back(l);
  }
  // Fewer sensors than a lidar: a sonar ring of five.
  {
    std::vector<RangeSensorSpec> l;
    for (int k = 0; k < 5; ++k) l.push_back(single(Vec2(0.1, 0.0), k * 0.5, 2.0));
    lists.push_back(l);
  }
  // Uneven headings on one mount point (a fan without a lidar), and a run of 15 (no lidar).
  {
    std::vector<RangeSensorSpec> l;
    Rng rng(4);
    for (int k = 0; k < 30; ++k) l.push_back(single(Vec2(0.0, 0.0), rng.uniform(-kPi, kPi), 3.0));
    append(l, make_lidar(15, 1.0, 0.0, 3.0, {Vec2(0.3, 0.0), 0.0}));
    lists.push_back(l);
  }
  return lists;
}

TEST(SensorLayout, FindsTheLidarsAndFansOfAMixedList) {
  std::vector<RangeSensorSpec> l;
  for (int k = 0; k < 3; ++k) l.push_back(cone(Vec2(0.1, 0.0), k * 0.5));  // 0..2: cones
  append(l, make_lidar(20, 1.0, 0.1, 4.0, {Vec2(0.1, 0.0), 0.0}));         // 3..22: a lidar
  l.push_back(single(Vec2(0.1, 0.0), 3.0, 4.0));  // 23: its mount point and range, off its turn
  l.push_back(single(Vec2(0.1, 0.0), 3.0, 2.0));  // 24: another range
  append(l, make_lidar(16, 1.0, 0.1, 2.0, {Vec2(0.1, 0.0), 2.0}));  // 25..40: a second lidar
  const SensorLayout layout(l);
  ASSERT_EQ(layout.size(), l.size());
  ASSERT_EQ(layout.lidars().size(), 2u);
  EXPECT_EQ(layout.lidars()[0].begin, 3u);
  EXPECT_EQ(layout.lidars()[0].end, 23u);
  EXPECT_EQ(layout.lidars()[1].begin, 25u);
  EXPECT_EQ(layout.lidars()[1].end, 41u);
  // The turn: 1 rad over 19 gaps.
  EXPECT_EQ(layout.lidars()[0].turn.x(), std::cos(1.0 / 19.0));
  EXPECT_EQ(layout.lidars()[0].turn.y(), std::sin(1.0 / 19.0));
  // A cone is no fan; the first lidar's fan takes in sensor 23; 24 starts the second's.
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(layout.fan_end(i), i) << i;
  for (std::size_t i = 3; i < 24; ++i) EXPECT_EQ(layout.fan_end(i), 24u) << i;
  for (std::size_t i = 24; i < l.size(); ++i) EXPECT_EQ(layout.fan_end(i), l.size()) << i;
  EXPECT_EQ(layout.min_ranges()[0], 0.02);
  EXPECT_EQ(layout.max_ranges()[24], 2.0);
  // Neither fan is evenly spaced: sensor 23 is off the first lidar's turn, 24 off the second's.
  EXPECT_FALSE(layout.even_run(3));
  EXPECT_FALSE(layout.even_run(24));
  // Fewer than 16 sensors: no lidar, whatever their headings.
  const auto ring = make_lidar(15, 1.0, 0.1, 4.0, {Vec2(0.0, 0.0), 0.0});
  EXPECT_TRUE(SensorLayout(ring).lidars().empty());
  EXPECT_EQ(SensorLayout(ring).fan_end(0), 15u);
}

// A lidar's run is evenly spaced, a full turn included (its mount angles wrap past pi); one
// beam 1e-6 rad off its place makes the run uneven, and its fans check their beams again.
TEST(SensorLayout, KnowsWhichRunsAreEvenlySpaced) {
  const auto full = make_lidar(180, 2.0 * kPi, 0.12, 3.5, {Vec2(-0.032, 0.0), 0.0});
  EXPECT_TRUE(SensorLayout(full).even_run(0));
  const auto half = make_lidar(180, kPi, 0.0, 8.0, {Vec2(0.13, 0.0), 2.5});
  EXPECT_TRUE(SensorLayout(half).even_run(0));
  auto bent = full;
  bent[90].mount.theta += 1e-6;
  EXPECT_FALSE(SensorLayout(bent).even_run(0));
}

TEST(SensorLayout, BeamsMatchThePlainFunction) {
  Rng rng(11);
  for (const auto& sensors : sensor_lists()) {
    const SensorLayout layout(sensors);
    std::vector<SensorBeam> plain(sensors.size()), laid(sensors.size());
    for (int i = 0; i < 200; ++i) {
      // Headings also far outside (-pi, pi]: the per-beam wrap turns more than once.
      const double theta = i % 10 == 0 ? rng.uniform(-30.0, 30.0) : rng.uniform(-kPi, kPi);
      const Pose2 robot{Vec2(rng.uniform(-50.0, 50.0), rng.uniform(-50.0, 50.0)), theta};
      compute_sensor_beams(robot, sensors, plain);
      compute_sensor_beams(robot, sensors, layout, laid);
      for (std::size_t k = 0; k < sensors.size(); ++k) {
        ASSERT_EQ(bits(plain[k].origin.x()), bits(laid[k].origin.x())) << i << " " << k;
        ASSERT_EQ(bits(plain[k].origin.y()), bits(laid[k].origin.y())) << i << " " << k;
        ASSERT_EQ(bits(plain[k].dir.x()), bits(laid[k].dir.x())) << i << " " << k;
        ASSERT_EQ(bits(plain[k].dir.y()), bits(laid[k].dir.y())) << i << " " << k;
        ASSERT_EQ(bits(plain[k].theta), bits(laid[k].theta)) << i << " " << k;
      }
    }
  }
}

// A single-beam sensor's heading is the exact sum of the robot's and the mount's, wrapped by
// whole turns (-2.5 + -2 is -4.5, i.e. 2pi - 4.5); its direction is the mount's (cos, sin) turned
// by the robot's, bit for bit, given or taken, and within 1e-15 of (cos, sin) of the heading. A
// sensor facing straight ahead (mount 0 or -0) has the robot's own cosine and sine.
TEST(SensorLayout, SingleBeamDirectionsAreTheMountTurnedByTheRobot) {
  std::vector<RangeSensorSpec> sensors(5);
  const double mounts[] = {0.0, -0.0, kPi / 2, -2.5, 3.0};
  for (std::size_t k = 0; k < sensors.size(); ++k) {
    sensors[k].mount = {Vec2(0.1, 0.0), mounts[k]};
    sensors[k].max_range = 0.3;
  }
  const SensorLayout layout(sensors);
  std::vector<SensorBeam> beams(sensors.size()), given(sensors.size()), plain(sensors.size());
  Rng rng(5);
  for (int i = 0; i < 300; ++i) {
    const double theta = i == 0 ? -0.0 : i == 1 ? 0.0 : i == 2 ? -2.0 : rng.uniform(-kPi, kPi);
    const Pose2 robot{Vec2(rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0)), theta};
    const double c = std::cos(theta), s = std::sin(theta);
    compute_sensor_beams(robot, sensors, layout, beams);
    compute_sensor_beams(robot, Vec2(c, s), sensors, layout, given);
    compute_sensor_beams(robot, sensors, plain);
    for (std::size_t k = 0; k < sensors.size(); ++k) {
      double heading = theta + mounts[k];
      if (heading > kPi) heading -= 2.0 * kPi;
      if (heading <= -kPi) heading += 2.0 * kPi;
      ASSERT_EQ(bits(beams[k].theta), bits(heading)) << i << " " << k;
      EXPECT_NEAR(beams[k].theta, wrap_angle(theta + mounts[k]), 1e-15) << i << " " << k;
      const double mc = std::cos(mounts[k]), ms = std::sin(mounts[k]);
      ASSERT_EQ(bits(beams[k].dir.x()), bits(c * mc - s * ms)) << i << " " << k;
      ASSERT_EQ(bits(beams[k].dir.y()), bits(s * mc + c * ms)) << i << " " << k;
      EXPECT_NEAR(beams[k].dir.x(), std::cos(heading), 1e-15) << i << " " << k;
      EXPECT_NEAR(beams[k].dir.y(), std::sin(heading), 1e-15) << i << " " << k;
      if (mounts[k] == 0.0) {
        EXPECT_EQ(beams[k].dir.x(), c) << i << " " << k;
        EXPECT_EQ(beams[k].dir.y(), s) << i << " " << k;
      }
      for (const auto* other : {&given, &plain}) {
        ASSERT_EQ(bits((*other)[k].dir.x()), bits(beams[k].dir.x())) << i << " " << k;
        ASSERT_EQ(bits((*other)[k].dir.y()), bits(beams[k].dir.y())) << i << " " << k;
        ASSERT_EQ(bits((*other)[k].theta), bits(beams[k].theta)) << i << " " << k;
      }
    }
  }
  // The case worked by hand: robot at -2.0 rad, mount -2.5 rad: -4.5 + 2pi = 1.78318530718 rad.
  compute_sensor_beams(Pose2{Vec2::Zero(), -2.0}, sensors, layout, beams);
  EXPECT_NEAR(beams[3].theta, 1.7831853071795865, 1e-15);
  EXPECT_NEAR(beams[3].dir.x(), -0.2107957994307797, 1e-15);  // cos 1.78318530718
  EXPECT_NEAR(beams[3].dir.y(), 0.9775301176650970, 1e-15);   // sin 1.78318530718
}

// Mount angles far outside a turn (as a library user may pass them) wrap as wrap_angle does, to
// the rounding of the sum, and take no time: whole turns are taken only within a turn and a half.
TEST(SensorLayout, MountAnglesFarOutsideATurnWrapWithoutLooping) {
  std::vector<RangeSensorSpec> sensors(3);
  const double mounts[] = {1e300, -7.5, 40.0};
  for (std::size_t k = 0; k < sensors.size(); ++k) {
    sensors[k].mount = {Vec2::Zero(), mounts[k]};
    sensors[k].max_range = 1.0;
  }
  std::vector<SensorBeam> beams(sensors.size());
  compute_sensor_beams(Pose2{Vec2::Zero(), 3.0}, sensors, beams);
  for (std::size_t k = 0; k < sensors.size(); ++k) {
    EXPECT_GT(beams[k].theta, -kPi) << k;
    EXPECT_LE(beams[k].theta, kPi) << k;
    EXPECT_NEAR(beams[k].theta, wrap_angle(3.0 + mounts[k]), 1e-12) << k;
  }
  // -7.5 + 3 = -4.5: one turn up, 2pi - 4.5 = 1.783185307 rad.
  EXPECT_NEAR(beams[1].theta, 1.7831853071795865, 1e-15);
}

// A walled floor of boxes over a sparse occupancy grid.
std::unique_ptr<World> floor_world(Rng& rng, std::shared_ptr<const OccupancyGrid>& grid) {
  WorldDesc d;
  d.bounds = Box2{Vec2(-6.0, -6.0), Vec2(6.0, 6.0)};
  for (int p = 0; p < 12; ++p) {
    const Vec2 c(rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0));
    const double h = rng.uniform(0.1, 0.6);
    d.polygons.push_back({c + Vec2(-h, -h), c + Vec2(h, -h), c + Vec2(h, h), c + Vec2(-h, h)});
  }
  std::vector<std::uint8_t> cells(60 * 60);
  for (auto& c : cells) c = rng.uniform() < 0.02 ? 1 : 0;
  grid = std::make_shared<const OccupancyGrid>(60, 60, 0.2, Pose2{Vec2(-6.0, -6.0), 0.0}, cells);
  d.grid = grid;
  return std::make_unique<World>(std::move(d));
}

TEST(SensorLayout, RangesAndNoiseMatchThePlainFunction) {
  Rng rng(23);
  std::shared_ptr<const OccupancyGrid> grid;
  const std::unique_ptr<World> world = floor_world(rng, grid);
  FanScratch scratch;
  for (const auto& sensors : sensor_lists()) {
    const SensorLayout layout(sensors);
    std::vector<SensorBeam> beams(sensors.size());
    std::vector<double> plain(sensors.size()), laid(sensors.size());
    for (int i = 0; i < 120; ++i) {
      const Pose2 robot{Vec2(rng.uniform(-5.5, 5.5), rng.uniform(-5.5, 5.5)),
                        rng.uniform(-kPi, kPi)};
      compute_sensor_beams(robot, sensors, layout, beams);
      // Other bodies and a forklift on some steps; noise on half of them (the noiseless clamp is
      // the layout's own path); a free disc on some.
      std::vector<Circle> others;
      std::vector<OrientedBox> boxes;
      if (i % 3 == 0)
        for (int k = 0; k < 4; ++k)
          others.push_back({robot.position + Vec2(rng.uniform(-3, 3), rng.uniform(-3, 3)), 0.3});
      if (i % 4 == 1)
        boxes.push_back(OrientedBox::make(robot.position + Vec2(1.0, 0.5), Vec2(1.6, 0.4), 0.2));
      const double noise = i % 2 == 0 ? 0.0 : 0.02;
      const FreeDisc free{robot.position, i % 5 == 0 ? 0.2 : 0.0};
      Rng a(500 + i), b(500 + i);
      sense_ranges(*world, beams, sensors, noise, a, plain, scratch, free, others, boxes);
      sense_ranges(*world, beams, sensors, layout, noise, b, laid, scratch, free, others, boxes);
      for (std::size_t k = 0; k < sensors.size(); ++k)
        ASSERT_EQ(bits(plain[k]), bits(laid[k])) << "pose " << i << " sensor " << k;
      EXPECT_EQ(a.normal(), b.normal());  // the same number of draws
    }
  }
}

TEST(SensorLayout, MountPointsThatMeetByRoundingMakeOneFanAsInThePlainFunction) {
  // A lidar and a ring of singles on mount points one ulp apart: far from the origin their
  // origins round to the same point and fan_end runs on into the ring, so the layout's fan end
  // (the lidar's mount point) is extended at run time, up to the ring's end and no further.
  // (Fans give the ranges of casting ray by ray, so the grouping does not show in the ranges;
  // an extension past the ring, onto the cone after it, would.)
  const double a = 0.1, b = std::nextafter(0.1, 1.0);
  auto sensors = make_lidar(20, 1.0, 0.0, 3.0, {Vec2(a, 0.0), 0.0});
  for (int k = 0; k < 20; ++k) sensors.push_back(single(Vec2(b, 0.0), 2.0 + 0.05 * k, 3.0));
  sensors.push_back(cone(Vec2(b, 0.0), 0.0));
  const SensorLayout layout(sensors);
  ASSERT_EQ(layout.fan_end(0), 20u);
  Rng rng(2);
  std::shared_ptr<const OccupancyGrid> grid;
  const std::unique_ptr<World> world = floor_world(rng, grid);
  std::vector<SensorBeam> beams(sensors.size());
  std::vector<double> plain(sensors.size()), laid(sensors.size());
  FanScratch scratch;
  for (const Pose2& robot : {Pose2{Vec2(1000.0, 0.0), 0.0}, Pose2{Vec2(0.0, 1.0), 0.0}}) {
    compute_sensor_beams(robot, sensors, layout, beams);
    Rng r1(3), r2(3);
    sense_ranges(*world, beams, sensors, 0.01, r1, plain, scratch);
    sense_ranges(*world, beams, sensors, layout, 0.01, r2, laid, scratch);
    for (std::size_t k = 0; k < sensors.size(); ++k) ASSERT_EQ(bits(plain[k]), bits(laid[k])) << k;
    EXPECT_EQ(r1.normal(), r2.normal());
  }
  // The premise: at x = 1000 the two mount points give one origin, near the origin two.
  std::vector<SensorBeam> far(sensors.size()), near(sensors.size());
  compute_sensor_beams(Pose2{Vec2(1000.0, 0.0), 0.0}, sensors, layout, far);
  compute_sensor_beams(Pose2{Vec2(0.0, 1.0), 0.0}, sensors, layout, near);
  EXPECT_EQ(far[0].origin, far[20].origin);
  EXPECT_NE(near[0].origin, near[20].origin);
}

TEST(SensorLayout, NoiselessFanIsClampedToEachSensorsRange) {
  // A lidar whose beams have a min_range of their own: every reading within [min, max], those
  // against the near wall at the min, and a beam that sees nothing reads exactly max_range.
  std::vector<RangeSensorSpec> sensors = make_lidar(32, kPi, 0.0, 3.0, {Vec2(0.0, 0.0), 0.0});
  for (std::size_t k = 0; k < sensors.size(); ++k) sensors[k].min_range = k % 2 == 0 ? 0.5 : 0.0;
  WorldDesc d;
  d.polygons.push_back({{0.2, -1.0}, {0.3, -1.0}, {0.3, 1.0}, {0.2, 1.0}});  // a wall 0.2 m ahead
  const World world(std::move(d));
  const SensorLayout layout(sensors);
  std::vector<SensorBeam> beams(sensors.size());
  compute_sensor_beams(Pose2{Vec2(0.0, 0.0), 0.0}, sensors, layout, beams);
  std::vector<double> ranges(sensors.size());
  Rng rng(1);
  FanScratch scratch;
  sense_ranges(world, beams, sensors, layout, 0.0, rng, ranges, scratch);
  // Beams 15 and 16 straddle the heading (+-pi/62): they meet the wall at 0.2 / cos(pi/62).
  const double hit = 0.2 / std::cos(kPi / 62.0);
  EXPECT_NEAR(ranges[15], hit, 1e-12);  // odd: no min
  EXPECT_EQ(ranges[16], 0.5);           // even: clamped up to its min
  EXPECT_EQ(ranges[0], 3.0);            // straight to the right: nothing within 3 m
  for (std::size_t k = 0; k < sensors.size(); ++k) {
    EXPECT_GE(ranges[k], sensors[k].min_range) << k;
    EXPECT_LE(ranges[k], 3.0) << k;
  }
}

}  // namespace
}  // namespace floornav
