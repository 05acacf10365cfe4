// Outcomes of the planning layer and DWA in whole runs: the planner reaches a goal the chapter's
// automaton alone does not reach in time, DWA reaches a simple goal, a walled-off goal ends
// `stuck` on a known map.
#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/nav/sampling_planner.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/scenario/validate.hpp"

using namespace floornav;

namespace {
Scenario make(const std::string& preset, WorldDesc desc, Pose2 start, Vec2 goal, double t_max) {
  const RobotPreset p = *find_robot_preset(preset);
  Scenario s;
  s.name = "planner-test";
  s.world = std::make_shared<const World>(std::move(desc));
  RobotTask& t = s.robots.emplace_back();
  t.robot = p.robot;
  t.controller.params = p.navigation;
  t.start = start;
  t.goals = {goal};
  s.sim.dt = 0.05;
  s.sim.t_max = t_max;
  return s;
}

// A long wall between start and goal, joined to the west wall of the hall and open only at its
// east end, tilted so that eqs. 5.23/5.24 turn the automaton west: the long way, round the whole
// hall.
WorldDesc long_way() {
  WorldDesc d;
  d.bounds = Box2{Vec2(-8, -1), Vec2(4, 6)};
  d.polygons.push_back({{-8, 3.3}, {2, 2.3}, {2, 2.5}, {-8, 3.5}});
  return d;
}

double time_in(const RunResult& r, const std::string& mode) {
  for (std::size_t i = 0; i < r.mode_names.size(); ++i)
    if (r.mode_names[i] == mode) return r.mode_time[i];
  return 0.0;
}

// The planner took the short way: reached, untouched, shorter than `max_length`, without backing
// up.
void expect_short_way(const RunResult& planned, double max_length) {
  EXPECT_EQ(planned.status, RunStatus::Reached);
  EXPECT_FALSE(planned.collided);
  EXPECT_GT(planned.min_clearance, 0.0);
  EXPECT_LT(planned.path_length, max_length);
  EXPECT_EQ(time_in(planned, "recovery_back_up"), 0.0);
}

// Two runs of one scenario, sample by sample, bit for bit.
void expect_same_trajectory(const RunResult& a, const RunResult& b) {
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    ASSERT_EQ(a.trajectory[i].x, b.trajectory[i].x) << i;
    ASSERT_EQ(a.trajectory[i].y, b.trajectory[i].y) << i;
    ASSERT_EQ(a.trajectory[i].theta, b.trajectory[i].theta) << i;
  }
}
}  // namespace

TEST(PlannerOutcomes, PlannerReachesAGoalTheChapterAloneDoesNotReachInTime) {
  Scenario s = make("turtlebot3_burger", long_way(), {Vec2(0, 0), kPi / 2}, Vec2(0, 5), 120.0);
  const RunResult alone = simulate(s);
  EXPECT_EQ(alone.status, RunStatus::Timeout) << "the chapter alone goes the long way";
  EXPECT_FALSE(alone.collided);

  s.robot().controller.planner.kind = PlannerKind::AStar;
  // East round the end of the wall: about 6.5 m; the chapter alone drove 24 m and timed out.
  expect_short_way(simulate(s), 8.0);

  // Mapless, from its own lidar only: it finds the way too.
  s.robot().controller.planner.map = PlannerMap::Sensed;
  const RunResult sensed = simulate(s);
  EXPECT_EQ(sensed.status, RunStatus::Reached);
  EXPECT_FALSE(sensed.collided);
  EXPECT_LT(sensed.path_length, 10.0);
}

TEST(PlannerOutcomes, SameScenarioSameTrajectoryBitForBit) {
  Scenario s = make("turtlebot3_burger", long_way(), {Vec2(0, 0), kPi / 2}, Vec2(0, 5), 60.0);
  s.robot().controller.planner.kind = PlannerKind::AStar;
  s.robot().controller.planner.map = PlannerMap::Sensed;
  const RunResult a = simulate(s), b = simulate(s);
  expect_same_trajectory(a, b);
}

TEST(PlannerOutcomes, DwaReachesASimpleGoal) {
  WorldDesc d;
  d.bounds = Box2{Vec2(0, 0), Vec2(5, 4)};
  // Beside the straight line: the body passes 0.095 m from it. (Across the line, DWA alone
  // stops in front of it: the local minimum, see docs/BENCHMARKS.md.)
  d.circles.push_back({Vec2(2.5, 2.6), 0.4});
  Scenario s = make("turtlebot3_burger", d, {Vec2(0.5, 2.0), 0.0}, Vec2(4.5, 2.0), 60.0);
  s.robot().controller.kind = "dwa";
  const RunResult r = simulate(s);
  EXPECT_EQ(r.status, RunStatus::Reached);
  EXPECT_FALSE(r.collided);
  EXPECT_GT(r.min_clearance, 0.0);
  EXPECT_GT(time_in(r, "dwa"), 0.0);
  EXPECT_LT(r.sim_time, 40.0);
}

// The goal stands in a closed room.
WorldDesc walled_off() {
  WorldDesc d;
  d.bounds = Box2{Vec2(0, 0), Vec2(6, 4)};
  d.polygons.push_back(make_rectangle(Vec2(4.5, 1.0), Vec2(2.0, 0.1), 0.0));
  d.polygons.push_back(make_rectangle(Vec2(4.5, 3.0), Vec2(2.0, 0.1), 0.0));
  d.polygons.push_back(make_rectangle(Vec2(3.5, 2.0), Vec2(0.1, 2.1), 0.0));
  d.polygons.push_back(make_rectangle(Vec2(5.5, 2.0), Vec2(0.1, 2.1), 0.0));
  return d;
}

// Either planner on the known map: no path (astar: none exists; rrt_connect: none within its
// budget of samples), so the run stops at once, before a step.
struct WalledOffCase {
  const char* name;
  PlannerKind kind;
  int max_samples;  ///< 0: the default
  const char* why;
};
void PrintTo(const WalledOffCase& c, std::ostream* os) {
  *os << c.name;
}

class WalledOffKnownMap : public ::testing::TestWithParam<WalledOffCase> {};

TEST_P(WalledOffKnownMap, GoalIsStuckAtOnce) {
  Scenario s =
      make("turtlebot3_burger", walled_off(), {Vec2(1.0, 2.0), 0.0}, Vec2(4.5, 2.0), 120.0);
  PlannerParams& planner = s.robot().controller.planner;
  planner.kind = GetParam().kind;
  if (GetParam().max_samples > 0) planner.max_samples = GetParam().max_samples;
  const RunResult r = simulate(s);
  EXPECT_EQ(r.status, RunStatus::Stuck);
  EXPECT_FALSE(r.collided);
  EXPECT_EQ(r.steps, 0) << GetParam().why;
}

INSTANTIATE_TEST_SUITE_P(
    PlannerOutcomes, WalledOffKnownMap,
    ::testing::Values(WalledOffCase{"astar", PlannerKind::AStar, 0,
                                    "no path on the known map: nothing to try"}
#if FLOORNAV_WITH_OMPL
                      ,
                      WalledOffCase{"rrt_connect", PlannerKind::RrtConnect, 3000,
                                    "no path within the budget: the same as astar finding none"}
#endif
                      ),
    [](const ::testing::TestParamInfo<WalledOffCase>& info) { return info.param.name; });

// The chapter alone circles the room until the simulator's own stuck or time limit.
TEST(PlannerOutcomes, WalledOffGoalTheChapterAloneCircles) {
  Scenario s =
      make("turtlebot3_burger", walled_off(), {Vec2(1.0, 2.0), 0.0}, Vec2(4.5, 2.0), 120.0);
  s.robot().controller.planner.kind = PlannerKind::None;
  const RunResult alone = simulate(s);
  EXPECT_NE(alone.status, RunStatus::Reached);
  EXPECT_GT(alone.steps, 100);
}

// Mapless, the walls are learnt beam by beam (and grazing beams wear them down), so the robot
// tries and recovers; it never gets in, and never touches a wall.
TEST(PlannerOutcomes, WalledOffGoalOnTheSensedMapIsNotReachedAndRecoveriesAreTried) {
  Scenario s =
      make("turtlebot3_burger", walled_off(), {Vec2(1.0, 2.0), 0.0}, Vec2(4.5, 2.0), 120.0);
  s.robot().controller.planner.kind = PlannerKind::AStar;
  s.robot().controller.planner.map = PlannerMap::Sensed;
  const RunResult r = simulate(s);
  EXPECT_NE(r.status, RunStatus::Reached);
  EXPECT_FALSE(r.collided);
  EXPECT_GT(time_in(r, "recovery_back_up"), 0.0);
}

// BARN world 180 (Perille et al. 2020; the BARN challenge's worlds, MIT, (c) 2022 Zifan Xu): its
// cylinders (r = 0.075 m) on BARN's 0.15 m grid, row 0 at y = 9.525, column 0 at x = -4.425,
// '#' a cylinder. The Jackal from (-2, 3) to (-2, 13) with the BARN template's controller
// (scenarios/barn_template.yaml) under the planner on its rolling grid.
namespace {
Scenario barn_world_180() {
  static constexpr const char* kRows[] = {
      "#............................#", "#...........##...............#",
      "###..........#.........##...##", "##.##..................#...###",
      "##..##....................####", "#...........................##",
      "#..##.......................##", "#..#.......................###",
      "#...#........####...........##", "#............#####...........#",
      "##.....#..##..##.............#", "##....###..#...........###...#",
      "###...##................#...##", "##...........................#",
      "##...........................#", "##..........................##",
      "##........................####", "#........................#####",
      "#..####..................#..##", "#..#####.....................#",
      "#.....###....................#", "##.#...##......##.####......##",
      "###......#.....####.###...####", "##...............####....#.###",
      "##...............#..#.....#.##", "##.........................###",
      "###..........................#", "##....................#......#",
      "#...#................###.....#", "#..##...............##.......#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "#............................#",
      "#............................#", "##############################",
  };
  WorldDesc d;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 30; ++i)
      if (kRows[j][i] == '#')
        d.circles.push_back({Vec2(-4.425 + 0.15 * i, 9.525 - 0.15 * j), 0.075});
  Scenario s = make("jackal", std::move(d), {Vec2(-2, 3), 1.5708}, Vec2(-2, 13), 100.0);
  NavigationParams& p = s.robot().controller.params;
  p.epsilon = 1.0;
  p.clear_shot_corridor = 1.0;
  p.footprint_clearance = true;
  p.d_o = 0.3;
  p.d_fb = 0.15;
  p.d_unsafe = 0.04;
  p.hysteresis = 0.04;
  p.obstacle_range = 0.4;
  s.robot().controller.planner.kind = PlannerKind::AStar;
  s.robot().controller.planner.map = PlannerMap::Sensed;
  return s;
}
}  // namespace

// In a gap barely wider than the Jackal, the automaton turns on the spot (avoid-obstacle and
// go-to-goal taking turns) and the recovery then backs up into a cylinder in the lidar's blind
// sector: a collision. With the footprint guard the same stack slows or changes each command that
// would bring the rectangle within 2 cm of a sensed or remembered point, and gets through.
TEST(PlannerOutcomes, FootprintGuardGetsTheJackalThroughAGapWhereTheStackWithoutItTouches) {
  Scenario s = barn_world_180();
  s.robot().controller.safety.enabled = false;  // the planner stack alone
  const RunResult unguarded = simulate(s);
  EXPECT_EQ(unguarded.status, RunStatus::Collision);
  EXPECT_TRUE(unguarded.collided);

  s.robot().controller.planner.guard_horizon = 0.5;
  const RunResult guarded = simulate(s);
  EXPECT_EQ(guarded.status, RunStatus::Reached);
  EXPECT_FALSE(guarded.collided);
  EXPECT_GT(guarded.min_clearance, 0.0) << "the rectangle never touches a cylinder";
  // It passes where the unguarded run ended: north of y = 6.5, within the 100 s.
  ASSERT_FALSE(guarded.trajectory.empty());
  EXPECT_GT(guarded.trajectory.back().y, 12.0);
  EXPECT_LT(guarded.sim_time, 40.0);
}

#if FLOORNAV_WITH_OMPL
// The rrt_connect kind (OMPL's RRT-Connect on the same raster): a QuickBot finds the short way
// round the wall of long_way() that the chapter alone misses, and the same seed gives the same
// run bit for bit.
TEST(PlannerOutcomes, RrtConnectQuickBotTakesTheShortWayTheChapterAloneMisses) {
  Scenario s = make("quickbot", long_way(), {Vec2(0, 0), kPi / 2}, Vec2(0, 5), 150.0);
  const RunResult alone = simulate(s);
  EXPECT_NE(alone.status, RunStatus::Reached) << "the chapter alone goes the long way";

  s.robot().controller.planner.kind = PlannerKind::RrtConnect;
  // East round the end of the wall (about 6.5 m, as astar's); string pulling straightens the
  // sampled path, so it is not much longer.
  expect_short_way(simulate(s), 9.0);
}

TEST(PlannerOutcomes, RrtConnectSameSeedSameTrajectoryBitForBit) {
  // Mapless: many plans (each path is checked every second and replanned when blocked).
  Scenario s = make("turtlebot3_burger", long_way(), {Vec2(0, 0), kPi / 2}, Vec2(0, 5), 150.0);
  s.robot().controller.planner.kind = PlannerKind::RrtConnect;
  s.robot().controller.planner.map = PlannerMap::Sensed;
  s.sim.seed = 11;
  const RunResult a = simulate(s), b = simulate(s);
  // It gets there, the long way: 17.2 m where astar drives 6.8 m (docs/SCENARIOS.md says why).
  EXPECT_EQ(a.status, RunStatus::Reached);
  EXPECT_FALSE(a.collided);
  expect_same_trajectory(a, b);
}
#endif

// `planner.kind: rrt_connect` runs whatever search is installed (nav/sampling_planner.hpp):
// floornav::ompl's, or here a stand-in, so that the hook is tested in builds with and without
// OMPL. The previous search is put back afterwards.
class InstalledSearch {
 public:
  explicit InstalledSearch(SampledPathSearch search) : saved_(rrt_connect_search()) {
    set_rrt_connect_search(search);
  }
  ~InstalledSearch() { set_rrt_connect_search(saved_); }
  InstalledSearch(const InstalledSearch&) = delete;
  InstalledSearch& operator=(const InstalledSearch&) = delete;

 private:
  SampledPathSearch saved_;
};

int g_straight_searches = 0;
// The straight line between the two cells: right in an empty hall.
bool straight_search(const FreeRaster&, GridCell start, GridCell goal, std::uint64_t, int,
                     std::vector<Vec2>& out) {
  ++g_straight_searches;
  out = {Vec2(start.x + 0.5, start.y + 0.5), Vec2(goal.x + 0.5, goal.y + 0.5)};
  return true;
}

Scenario empty_hall_with_rrt_connect() {
  WorldDesc hall;
  hall.bounds = Box2{Vec2(-1, -1), Vec2(6, 4)};
  Scenario s = make("turtlebot3_burger", std::move(hall), {Vec2(0, 0), 0.0}, Vec2(4, 2), 60.0);
  s.robot().controller.planner.kind = PlannerKind::RrtConnect;
  return s;
}

TEST(PlannerOutcomes, RrtConnectRunsTheInstalledSearch) {
  const InstalledSearch installed(&straight_search);
  g_straight_searches = 0;
  const Scenario s = empty_hall_with_rrt_connect();
  EXPECT_NO_THROW(validate_scenario(s, "hall.yaml"));
  const RunResult r = simulate(s);
  EXPECT_EQ(r.status, RunStatus::Reached);
  EXPECT_GE(g_straight_searches, 1) << "the planner did not ask the installed search";
}

// Without a search (a build without OMPL, or a program that does not link floornav::ompl):
// one clear error naming the key and OMPL, from validation and from the controller alike; never
// a run without its planner.
TEST(PlannerOutcomes, RrtConnectWithoutASearchIsBadInput) {
  const InstalledSearch none(nullptr);
  const Scenario s = empty_hall_with_rrt_connect();
  for (const bool validated : {true, false}) {
    SCOPED_TRACE(validated ? "validate_scenario" : "simulate");
    try {
      if (validated)
        validate_scenario(s, "hall.yaml");
      else
        (void)simulate(s);
      ADD_FAILURE() << "rrt_connect was accepted without a search";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("controller.planner.kind"), std::string::npos) << what;
      EXPECT_NE(what.find("needs OMPL"), std::string::npos) << what;
      EXPECT_NE(what.find("FLOORNAV_WITH_OMPL"), std::string::npos) << what;
    }
  }
  EXPECT_EQ(rrt_connect_search(), nullptr);
}
