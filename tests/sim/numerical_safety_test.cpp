// Numerical safety: no NaN or inf leaves a step, whatever the geometry. Property tests over
// random seeded floors, plus the degenerate cases by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "floornav/geometry/polygon.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/simulation.hpp"

using namespace floornav;

namespace {
void expect_all_finite(const RunResult& r) {
  ASSERT_TRUE(std::isfinite(r.sim_time));
  ASSERT_TRUE(std::isfinite(r.path_length));
  ASSERT_FALSE(std::isnan(r.min_clearance));
  for (const auto& s : r.trajectory) {
    ASSERT_TRUE(std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.theta)) << s.t;
    ASSERT_TRUE(std::isfinite(s.v) && std::isfinite(s.omega)) << s.t;
    ASSERT_TRUE(std::isfinite(s.w_left) && std::isfinite(s.w_right)) << s.t;
  }
}

Scenario base_scenario(WorldDesc desc, Pose2 start, Vec2 goal, ControllerKind kind) {
  const RobotPreset p = *find_robot_preset("quickbot");
  Scenario s;
  s.world = std::make_shared<const World>(std::move(desc));
  s.robots.emplace_back();
  s.robot().robot = p.robot;
  s.robot().controller.params = p.navigation;
  s.robot().start = start;
  s.robot().goals = {goal};
  s.robot().controller.kind = std::string(to_string(kind));
  s.sim.t_max = 40.0;
  return s;
}
}  // namespace

// Random floors of circles and rotated boxes; every kind of controller, noisy sensors.
// The count and seed are fixed so that a failure reproduces.
TEST(NumericalSafety, RandomFloorsNeverProduceNanOrInf) {
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const ControllerKind kinds[] = {ControllerKind::Hybrid, ControllerKind::HardSwitch,
                                  ControllerKind::Blended, ControllerKind::GoToGoal};
  int runs = 0;
  for (int i = 0; i < 40; ++i) {
    WorldDesc d;
    d.bounds = Box2{Vec2(0, 0), Vec2(3, 2)};
    for (int k = 0; k < 6; ++k) {
      if (u(rng) < 0.5)
        d.circles.push_back({Vec2(0.6 + 1.8 * u(rng), 0.2 + 1.6 * u(rng)), 0.02 + 0.2 * u(rng)});
      else
        d.polygons.push_back(make_rectangle(Vec2(0.6 + 1.8 * u(rng), 0.2 + 1.6 * u(rng)),
                                            Vec2(0.05 + 0.5 * u(rng), 0.05 + 0.3 * u(rng)),
                                            6.28 * u(rng)));
    }
    Scenario s = base_scenario(d, {Vec2(0.2, 0.2 + 1.6 * u(rng)), 6.28 * u(rng) - 3.14},
                               Vec2(2.8, 0.2 + 1.6 * u(rng)), kinds[i % 4]);
    if (s.world->clearance(s.robot().start.position) <= s.robot().robot.body_radius) continue;
    s.robot().robot.sensor_noise = 0.01 * u(rng);
    s.sim.seed = static_cast<std::uint64_t>(i);
    expect_all_finite(simulate(s));
    ++runs;
  }
  EXPECT_GT(runs, 20);
}

TEST(NumericalSafety, GoalExactlyAtTheStart) {
  WorldDesc d;
  d.bounds = Box2{Vec2(-1, -1), Vec2(1, 1)};
  for (auto kind : {ControllerKind::Hybrid, ControllerKind::Blended}) {
    const RunResult r = simulate(base_scenario(d, {Vec2(0, 0), 0.0}, Vec2(0, 0), kind));
    EXPECT_EQ(r.status, RunStatus::Reached);
    EXPECT_EQ(r.path_length, 0.0);
    expect_all_finite(r);
  }
}

TEST(NumericalSafety, RobotTouchingAWallEndsAsCollisionNotNan) {
  WorldDesc d;
  d.bounds = Box2{Vec2(0, 0), Vec2(2, 2)};
  Scenario s = base_scenario(d, {Vec2(0.075, 1.0), kPi}, Vec2(1.5, 1.0), ControllerKind::Hybrid);
  const RunResult r = simulate(s);  // the body exactly touches x = 0
  EXPECT_EQ(r.status, RunStatus::Collision);
  EXPECT_LE(r.min_clearance, 0.0);
  expect_all_finite(r);
}

TEST(NumericalSafety, SensorOnAnObstacleCorner) {
  // A box whose corner sits exactly on the front sensor's beam origin.
  WorldDesc d;
  d.bounds = Box2{Vec2(-1, -1), Vec2(2, 1)};
  d.polygons.push_back({Vec2(0.0664, 0.0), Vec2(0.4, 0.0), Vec2(0.4, 0.3), Vec2(0.0664, 0.3)});
  Scenario s = base_scenario(d, {Vec2(-0.2, -0.2), 0.0}, Vec2(1.5, -0.5), ControllerKind::Hybrid);
  expect_all_finite(simulate(s));
}
