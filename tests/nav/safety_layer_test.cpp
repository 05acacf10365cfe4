// The safety layer (nav/safety_layer.hpp) with values worked by hand: a QuickBot-sized disc
// (radius 0.075 m, braking at 1 m/s^2 and 10 rad/s^2, dt = 0.01 s, margin 0.01 m) against a wall,
// another robot, a person, and a footprint turning by a wall.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include "floornav/geometry/angle.hpp"
#include "floornav/nav/safety_layer.hpp"
#include "floornav/robot/body_clearance.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"
#include "support/property_count.hpp"

using namespace floornav;

namespace {

RobotSpec disc_robot() {
  RobotSpec r;
  r.drive = {.wheel_radius = 0.0325,
             .track_width = 0.09925,
             .max_wheel_speed = 13.6,
             .min_wheel_speed = 0.0};
  r.body_radius = 0.075;
  r.max_acceleration = 1.0;
  r.max_angular_acceleration = 10.0;
  return r;
}

// A walled room [-1, 1] x [-1, 1]: facing +x from (x, 0), the wall at x = 1 is the nearest.
World room() {
  WorldDesc d;
  d.bounds = Box2{Vec2(-1.0, -1.0), Vec2(1.0, 1.0)};
  return World(d);
}

SafetyScene scene_of(const World& w, const Pose2& pose, const RobotSpec& r) {
  SafetyScene s;
  s.world = &w;
  s.world_clearance = w.clearance(pose.position) - r.body_radius;
  return s;
}

constexpr double kDt = 0.01;

}  // namespace

// Driven for dt, then braked at a along the same arc: length v dt + v^2 / 2a, and the turn the
// arc's curvature w / v times that: w dt + w v / 2a. (0.15, 0.5): 0.0015 + 0.01125 = 0.01275 m
// and 0.005 + 0.0375 = 0.0425 rad. A turn on the spot stops with the step: (0, 2) turns 0.02.
TEST(SafetyLayer, TheStoppingPathIsOneStepThenBraking) {
  const RobotSpec r = disc_robot();
  const SafetyLayer layer(r, SafetyParams{}, kDt);
  const UnicycleCommand p = layer.stopping_path({0.15, 0.5});
  EXPECT_NEAR(p.v, 0.01275, 1e-15);
  EXPECT_NEAR(p.omega, 0.0425, 1e-15);
  EXPECT_NEAR(layer.stopping_path({0.0, 2.0}).omega, 0.02, 1e-15);
  const UnicycleCommand back = layer.stopping_path({-0.15, -0.5});
  EXPECT_NEAR(back.v, -0.01275, 1e-15);
  EXPECT_NEAR(back.omega, -0.0425, 1e-15);
  SafetyParams late;
  late.reaction_time = 0.1;  // 0.15 x 0.11 + 0.01125 = 0.02775
  EXPECT_NEAR(SafetyLayer(r, late, kDt).stopping_path({0.15, 0.0}).v, 0.02775, 1e-15);
}

// Far from the wall (0.425 m of clearance at x = 0.5) the bound alone answers:
// 0.425 - 0.01275 - 0.01 = 0.40225, and the command passes untouched.
TEST(SafetyLayer, FarFromEverythingACommandPassesUnchanged) {
  const RobotSpec r = disc_robot();
  const World w = room();
  const SafetyLayer layer(r, SafetyParams{}, kDt);
  const Pose2 pose{Vec2(0.5, 0.0), 0.0};
  const SafetyScene s = scene_of(w, pose, r);
  EXPECT_NEAR(layer.slack(pose, {0.15, 0.0}, s), 0.40225, 1e-12);
  const SafetyVerdict v = layer.filter(pose, {0.15, 0.3}, s);
  EXPECT_FALSE(v.limited);
  EXPECT_EQ(v.command.v, 0.15);
  EXPECT_EQ(v.command.omega, 0.3);
}

// 0.02 m from the wall, straight at it: the stopping path ends 0.02 - 0.01275 = 0.00725 m from
// it, 0.00275 inside the field. The fastest allowed speed solves 0.01 v + v^2 / 2 = 0.01:
// v = sqrt(0.0201) - 0.01 = 0.131774; the bisection finds it from below within 0.15 / 256.
TEST(SafetyLayer, NearAWallTheSpeedIsCutToWhatStopsAtTheField) {
  const RobotSpec r = disc_robot();
  const World w = room();
  const SafetyLayer layer(r, SafetyParams{}, kDt);
  const Pose2 pose{Vec2(1.0 - 0.075 - 0.02, 0.0), 0.0};
  const SafetyScene s = scene_of(w, pose, r);
  EXPECT_NEAR(layer.slack(pose, {0.15, 0.0}, s), -0.00275, 1e-12);
  const SafetyVerdict v = layer.filter(pose, {0.15, 0.0}, s);
  EXPECT_TRUE(v.limited);
  EXPECT_LE(v.command.v, std::sqrt(0.0201) - 0.01);
  EXPECT_GE(v.command.v, std::sqrt(0.0201) - 0.01 - 0.15 / 256.0);
  // What stopped it is reported where it is: the wall's nearest point.
  ASSERT_TRUE(v.blocked);
  EXPECT_NEAR(v.blocker.x(), 1.0, 1e-6);
  EXPECT_NEAR(v.blocker.y(), 0.0, 1e-6);
  // Backing away, or turning on the spot (a disc does not move), is left alone.
  EXPECT_FALSE(layer.filter(pose, {-0.15, 0.0}, s).limited);
  EXPECT_FALSE(layer.filter(pose, {0.0, 2.0}, s).limited);
}

// Inside the field already (0.005 m from the wall): no command may come nearer; moving away is
// allowed.
TEST(SafetyLayer, InsideTheFieldOnlyMovingAwayIsAllowed) {
  const RobotSpec r = disc_robot();
  const World w = room();
  const SafetyLayer layer(r, SafetyParams{}, kDt);
  const Pose2 pose{Vec2(1.0 - 0.075 - 0.005, 0.0), 0.0};
  const SafetyScene s = scene_of(w, pose, r);
  EXPECT_LT(layer.slack(pose, {0.01, 0.0}, s), 0.0);
  EXPECT_GE(layer.slack(pose, {-0.1, 0.0}, s), -1e-9);
  EXPECT_EQ(layer.filter(pose, {0.1, 0.0}, s).command.v, 0.0);
}

// Two robots running the layer, 0.1 m apart head on: each keeps to its half of the 0.09 m beyond
// the margin, so robot A's slack driving at B at 0.15 m/s is 0.045 - 0.01275 = 0.03225. A robot
// without the layer, which may come 0.0044 m in a step, leaves A 0.09 - 0.0044 - 0.01275.
TEST(SafetyLayer, AnotherRobotLeavesHalfTheRoomOrAllOfItLessItsStep) {
  const RobotSpec r = disc_robot();
  const SafetyLayer layer(r, SafetyParams{}, kDt);
  const Pose2 pose{Vec2(0.0, 0.0), 0.0};
  SafetyDisc other{Vec2(0.25, 0.0), 0.075, 0.0, true, 0.0, {}};
  SafetyScene s;
  s.discs = {&other, 1};
  EXPECT_NEAR(layer.slack(pose, {0.15, 0.0}, s), 0.03225, 1e-12);
  other.reciprocal = false;
  other.approach = 0.0044;
  EXPECT_NEAR(layer.slack(pose, {0.15, 0.0}, s), 0.09 - 0.0044 - 0.01275, 1e-12);
  // Driving past it (sideways) is left alone.
  EXPECT_FALSE(layer.filter(Pose2{Vec2(0.0, 0.0), kPi / 2.0}, {0.15, 0.0}, s).limited);
}

// A person 0.005 m from the robot's body, who may come 0.013 m in a step: standing keeps -0.013,
// so standing is no longer safe; driving straight away keeps more and is allowed as asked.
TEST(SafetyLayer, SomethingComingInLetsTheRobotGetAway) {
  const RobotSpec r = disc_robot();
  const SafetyLayer layer(r, SafetyParams{}, kDt);
  SafetyDisc person{Vec2(0.0, 0.0), 0.25, 0.013, false, 0.0, {}};
  SafetyScene s;
  s.discs = {&person, 1};
  const Pose2 pose{Vec2(0.25 + 0.075 + 0.005, 0.0), 0.0};  // facing away from the person
  EXPECT_NEAR(layer.slack(pose, {0.0, 0.0}, s), -0.013, 1e-12);
  const SafetyVerdict away = layer.filter(pose, {0.15, 0.0}, s);
  EXPECT_FALSE(away.limited);
  // Driving at the person is not; the layer takes the best way out instead (backing off too is
  // a way in): here it stands or turns, keeping at least what standing keeps.
  const SafetyVerdict at = layer.filter(Pose2{pose.position, kPi}, {0.15, 0.0}, s);
  EXPECT_TRUE(at.limited);
  EXPECT_GE(layer.slack(Pose2{pose.position, kPi}, at.command, s), -0.013 - 1e-9);
}

// A 0.5 x 0.4 m footprint 0.02 m from a wall turning on the spot at 10 rad/s: in one step of
// 0.01 s (0.1 rad) its corner (0.25, -0.2) swings 0.25 cos 0.1 + 0.2 sin 0.1 - 0.25 = 0.0187 m
// towards the wall, into the field: the turn is slowed (to about half), standing is allowed.
TEST(SafetyLayer, AFootprintIsNotSwungIntoAWall) {
  RobotSpec r = disc_robot();
  r.body_radius = 0.2;
  r.footprint = {{-0.25, -0.2}, {0.25, -0.2}, {0.25, 0.2}, {-0.25, 0.2}};
  const World w = room();
  const SafetyLayer layer(r, SafetyParams{}, kDt);
  const Pose2 pose{Vec2(1.0 - 0.27, 0.0), 0.0};  // the front face 0.02 m from the wall
  SafetyScene s;
  s.world = &w;
  s.world_clearance = 0.02;
  EXPECT_LT(layer.slack(pose, {0.0, 10.0}, s), 0.0);
  const SafetyVerdict v = layer.filter(pose, {0.0, 10.0}, s);
  EXPECT_TRUE(v.limited);
  EXPECT_GT(v.command.omega, 2.0);
  EXPECT_LT(v.command.omega, 8.0);
  EXPECT_GE(layer.slack(pose, v.command, s), -1e-9);
}

// The slow-down field caps the speed within its distance of anything, and only there.
TEST(SafetyLayer, TheSlowDownFieldCapsTheSpeedNearby) {
  const RobotSpec r = disc_robot();
  const World w = room();
  SafetyParams p;
  p.slowdown_distance = 0.3;
  p.slowdown_speed = 0.1;
  const SafetyLayer layer(r, p, kDt);
  const Pose2 near{Vec2(1.0 - 0.075 - 0.25, 0.0), kPi / 2.0};  // 0.25 m from the wall, beside it
  EXPECT_EQ(layer.filter(near, {0.3, 0.0}, scene_of(w, near, r)).command.v, 0.1);
  const Pose2 centre{Vec2(0.0, 0.0), 0.0};  // 0.925 m from every wall
  EXPECT_EQ(layer.filter(centre, {0.3, 0.0}, scene_of(w, centre, r)).command.v, 0.3);
}

namespace {

// A 4 x 4 m grid world of 0.05 m cells with a border and `blocks` random occupied squares.
World random_grid_world(std::mt19937_64& rng, int blocks) {
  constexpr int kCells = 80;
  std::vector<std::uint8_t> occupied(kCells * kCells, 0);
  for (int i = 0; i < kCells; ++i) {
    occupied[i] = occupied[(kCells - 1) * kCells + i] = 1;
    occupied[i * kCells] = occupied[i * kCells + kCells - 1] = 1;
  }
  std::uniform_int_distribution<int> cell(1, kCells - 8), size(1, 6);
  for (int b = 0; b < blocks; ++b) {
    const int x0 = cell(rng), y0 = cell(rng), w = size(rng), h = size(rng);
    for (int y = y0; y < y0 + h; ++y)
      for (int x = x0; x < x0 + w; ++x) occupied[y * kCells + x] = 1;
  }
  WorldDesc d;
  d.grid = std::make_shared<OccupancyGrid>(kCells, kCells, 0.05, Pose2{Vec2(-2.0, -2.0), 0.0},
                                           std::move(occupied));
  return World(d);
}

// The same room with `n` random discs instead.
World random_shape_world(std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> at(-1.8, 1.8), radius(0.02, 0.3);
  WorldDesc d;
  d.bounds = Box2{Vec2(-2.0, -2.0), Vec2(2.0, 2.0)};
  for (int i = 0; i < n; ++i) d.circles.push_back({Vec2(at(rng), at(rng)), radius(rng)});
  return World(d);
}

}  // namespace

// The filter passes a command unchanged exactly when its stopping path keeps the field, as the
// exact slack measures it: on generated grid and shape worlds with range returns scattered round
// the robot, for a disc and a footprint, at random poses (many of them within a stopping path of
// the field's edge, where a bound must not stand in for the path's samples), random commands up
// to the Pioneer's top speed and braking, and a scene whose bound on the world's clearance is as
// stale as a robot's between two exact checks. A command that is cut reports what blocked it.
TEST(SafetyLayer, TheFilterLimitsExactlyTheCommandsWhoseExactSlackMissesTheField) {
  std::mt19937_64 rng(20261207);
  RobotSpec disc = disc_robot();
  disc.max_acceleration = 0.3;  // long stopping paths (up to ~0.4 m): many samples
  RobotSpec boxed = disc;
  boxed.footprint = {Vec2(0.15, 0.1), Vec2(-0.15, 0.1), Vec2(-0.15, -0.1), Vec2(0.15, -0.1)};
  boxed.body_radius = 0.19;
  const SafetyLayer disc_layer(disc, SafetyParams{}, kDt), boxed_layer(boxed, SafetyParams{}, kDt);
  std::uniform_real_distribution<double> unit(0.0, 1.0), coord(-1.9, 1.9);
  const int worlds = test::property_count("FLOORNAV_SAFETY_FILTER_WORLDS", 40);
  int limited = 0, passed = 0;
  std::vector<Vec2> points;
  for (int k = 0; k < worlds; ++k) {
    const World w = k % 2 == 0 ? random_grid_world(rng, 30) : random_shape_world(rng, 25);
    for (int trial = 0; trial < 500; ++trial) {
      const bool footprint = trial % 2 == 1;
      const RobotSpec& r = footprint ? boxed : disc;
      const SafetyLayer& layer = footprint ? boxed_layer : disc_layer;
      const Pose2 pose{Vec2(coord(rng), coord(rng)), 2.0 * kPi * unit(rng)};
      const double clearance = body_clearance(w, r, pose);
      if (!(clearance > 0.0) || clearance > 0.6) continue;
      const UnicycleCommand c{0.5 * (2.0 * unit(rng) - 0.3), 2.0 * (2.0 * unit(rng) - 1.0)};
      // Every third scene has returns 0.2 to 1 m from the centre, beyond either body.
      points.clear();
      for (int i = 0; trial % 3 == 0 && i < 20; ++i) {
        const double a = 2.0 * kPi * unit(rng), d = 0.2 + 0.8 * unit(rng);
        points.push_back(pose.position + d * Vec2(std::cos(a), std::sin(a)));
      }
      SafetyScene s;
      s.world = &w;
      s.world_clearance = clearance - 0.6 * unit(rng);  // a lower bound, maybe a stale one
      s.points = points;
      const double exact = layer.slack(pose, c, s);
      const SafetyVerdict v = layer.filter(pose, c, s);
      ASSERT_EQ(v.limited, exact < -1e-9)
          << "world " << k << " trial " << trial << " slack " << exact << " at ("
          << pose.position.transpose() << "), command (" << c.v << ", " << c.omega << ")";
      if (!v.limited) {
        ++passed;
        continue;
      }
      ++limited;
      ASSERT_TRUE(v.blocked) << "world " << k << " trial " << trial;
    }
  }
  // Both kinds of answer were tested, many times.
  EXPECT_GT(limited, 20 * worlds);
  EXPECT_GT(passed, 20 * worlds);
}
