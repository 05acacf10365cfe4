// The corridor "clear shot" (NavigationParams::clear_shot_corridor), an extension for dense
// clutter: values worked by hand, its use by the automaton's guards, and its effect on a BARN
// world.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "floornav/geometry/angle.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/nav/navigation_automaton.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/simulation.hpp"

using namespace floornav;

namespace {

NavigationParams corridor_params(double length) {
  NavigationParams p;
  p.clear_shot_corridor = length;
  p.d_unsafe = 0.04;  // half-width = body radius 0.25 + 0.04 = 0.29 m
  return p;
}

bool blocked_by(const Vec2& point, double length = 1.0) {
  const std::vector<Vec2> points{point};
  return make_navigation_input(Vec2(0, 0), Vec2(2, 0), points, 0.25, corridor_params(length))
      .corridor_blocked;
}

// Robot at the origin, goal at (2, 0): the corridor is 0 < x < 1, |y| < 0.29.
TEST(ClearShotCorridor, APointInsideTheBodyWideCorridorBlocksIt) {
  EXPECT_TRUE(blocked_by(Vec2(1.0 - 1e-9, 0.0)));
  EXPECT_TRUE(blocked_by(Vec2(0.5, 0.28)));
  EXPECT_TRUE(blocked_by(Vec2(0.5, -0.28)));
  EXPECT_FALSE(blocked_by(Vec2(0.5, 0.30)));  // beside the corridor
  EXPECT_FALSE(blocked_by(Vec2(1.2, 0.0)));   // beyond its 1 m
  EXPECT_TRUE(blocked_by(Vec2(1.2, 0.0), 1.5));
  EXPECT_FALSE(blocked_by(Vec2(-0.3, 0.0)));      // behind the robot
  EXPECT_FALSE(blocked_by(Vec2(2.5, 0.0), 5.0));  // past the goal: the corridor ends there
}

TEST(ClearShotCorridor, OffByDefaultSoTheChapterTestDecides) {
  const std::vector<Vec2> points{Vec2(0.5, 0.0)};
  EXPECT_FALSE(make_navigation_input(Vec2(0, 0), Vec2(2, 0), points, 0.25, NavigationParams{})
                   .corridor_blocked);
}

// An obstacle beside the path that eq. 5.27 calls "in the way" (<u_AO, u_GTG> <= 0: it is a
// little ahead) does not start boundary following when the corridor is free, and does when the
// corridor is blocked.
TEST(ClearShotCorridor, GuardsUseTheCorridorInsteadOfEq5_27) {
  const NavigationParams p = corridor_params(1.0);
  const NavigationAutomaton chapter = make_navigation_automaton(ControllerKind::Hybrid, [] {
    NavigationParams q;
    q.d_unsafe = 0.04;
    return q;
  }());
  const NavigationAutomaton corridor = make_navigation_automaton(ControllerKind::Hybrid, p);
  NavigationInput in;
  in.goal = Vec2(2, 0);
  in.goal_distance = 2.0;
  in.u_gtg = Vec2(1, 0);
  in.u_ao = Vec2(-0.2, -1);  // obstacle above and a little ahead
  in.away = in.u_ao.normalized();
  in.obstacle_sensed = true;
  in.clearance = 0.05;  // within d_o (0.12), beyond d_unsafe (0.04)
  in.corridor_blocked = false;
  auto a = chapter.initial_state();
  EXPECT_TRUE(chapter.step(in, a, 0.01, 0.01).has_value());  // 5.27: not clear, follow
  auto b = corridor.initial_state();
  EXPECT_FALSE(corridor.step(in, b, 0.01, 0.01).has_value());  // corridor free: keep going
  in.corridor_blocked = true;
  EXPECT_TRUE(corridor.step(in, b, 0.02, 0.01).has_value());
  EXPECT_NE(corridor.modes()[b.mode].name, std::string(mode_names::kGoToGoal));
}

// Footprint clearance (NavigationParams::footprint_clearance): the Jackal's 0.508 x 0.430 m
// rectangle instead of its 0.25 m disc, worked by hand for a robot at the origin.
TEST(FootprintClearance, MeasuresFromTheRectangleTurnedWithTheRobot) {
  const std::vector<Vec2> jackal{
      {-0.254, -0.215}, {0.254, -0.215}, {0.254, 0.215}, {-0.254, 0.215}};
  NavigationParams p;
  p.footprint_clearance = true;
  auto clearance = [&](const Vec2& q, double heading, const NavigationParams& params) {
    const std::vector<Vec2> points{q};
    const BodyShape shape{jackal, heading};
    return make_navigation_input(Vec2(0, 0), Vec2(5, 0), points, 0.25, params, &shape).clearance;
  };
  EXPECT_NEAR(clearance(Vec2(0.3, 0.0), 0.0, p), 0.3 - 0.254, 1e-12);                // ahead
  EXPECT_NEAR(clearance(Vec2(0.0, 0.3), 0.0, p), 0.3 - 0.215, 1e-12);                // beside
  EXPECT_NEAR(clearance(Vec2(0.3, 0.25), 0.0, p), std::hypot(0.046, 0.035), 1e-12);  // the corner
  EXPECT_NEAR(clearance(Vec2(0.0, 0.3), kPi / 2, p), 0.3 - 0.254, 1e-12);  // turned: ahead again
  EXPECT_NEAR(clearance(Vec2(0.1, 0.0), 0.0, p), -(0.254 - 0.1), 1e-12);   // inside: negative
  // Off (the chapter): the disc, 0.3905 - 0.25 at the corner point.
  EXPECT_NEAR(clearance(Vec2(0.3, 0.25), 0.0, NavigationParams{}), std::hypot(0.3, 0.25) - 0.25,
              1e-12);
}

// BARN world 150, the chapter's automaton alone (no planner): with the template's corridor the
// Jackal gets through; with the chapter's clear shot it follows the cylinders round the arena
// until the 100 s run out.
TEST(ClearShotCorridor, BarnWorld150IsReachedOnlyWithTheCorridor) {
  const std::filesystem::path world =
      std::filesystem::path(FLOORNAV_MAPS_DIR) / "barn/world_files/world_150.world";
  const std::string templ = std::string(FLOORNAV_SCENARIO_DIR) + "/barn_template.yaml";
  const std::string map = "world.map=" + std::filesystem::absolute(world).string();
  const std::string chapter = "controller.preset=chapter";
  const RunResult with =
      simulate(load_scenario_file(templ, std::vector<std::string>{map, chapter}));
  const RunResult without = simulate(load_scenario_file(
      templ, std::vector<std::string>{map, chapter, "controller.clear_shot_corridor=0"}));
  EXPECT_EQ(with.status, RunStatus::Reached);
  EXPECT_LT(with.sim_time, 20.0);
  EXPECT_EQ(without.status, RunStatus::Timeout);
}

}  // namespace
