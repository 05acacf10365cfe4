// Scenario outcome tests: each chapter figure's scenario behaves as the chapter says.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/simulation.hpp"

using namespace floornav;

namespace {
RunResult run(const std::string& file, std::vector<std::string> sets = {}) {
  const Scenario s = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + file, sets);
  return simulate(s);
}
double time_in(const RunResult& r, const std::string& mode) {
  for (std::size_t i = 0; i < r.mode_names.size(); ++i)
    if (r.mode_names[i] == mode) return r.mode_time[i];
  return 0.0;
}
bool used_follow_boundary(const RunResult& r) {
  return time_in(r, "follow_boundary_cw") + time_in(r, "follow_boundary_ccw") > 0.0;
}
}  // namespace

class ChapterScenario : public ::testing::TestWithParam<const char*> {};

// The complete automaton (Fig 5.11) reaches every chapter goal without touching anything.
TEST_P(ChapterScenario, HybridReachesTheGoalWithoutCollision) {
  const RunResult r = run(GetParam(), {"controller.kind=hybrid"});
  EXPECT_EQ(r.status, RunStatus::Reached) << GetParam();
  EXPECT_FALSE(r.collided);
  EXPECT_GT(r.min_clearance, 0.0);
  EXPECT_EQ(r.chatter_episodes, 0) << "no Zeno behaviour with follow-boundary";
}

// Go-to-goal alone drives into whatever stands on the straight line (the chapter's robot, the
// safety layer off); with the safety layer, as shipped, it stops at its protective field instead
// and never touches.
TEST_P(ChapterScenario, GoToGoalAloneCollides) {
  const RunResult r = run(GetParam(), {"controller.kind=go_to_goal", "controller.safety=off"});
  EXPECT_EQ(r.status, RunStatus::Collision) << GetParam();
  EXPECT_LE(r.min_clearance, 0.0);
  const RunResult safe = run(GetParam(), {"controller.kind=go_to_goal"});
  EXPECT_FALSE(safe.collided) << GetParam();
  EXPECT_GT(safe.min_clearance, 0.0) << GetParam();
  EXPECT_GT(safe.safety_time, 0.0) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Figures, ChapterScenario,
                         ::testing::Values("point_obstacle.yaml", "circle_obstacle.yaml",
                                           "rectangle.yaml", "convex_obstacle.yaml",
                                           "concave_obstacle.yaml", "factory_delivery.yaml",
                                           "coppeliasim_pioneer.yaml", "week7_pocket.yaml",
                                           "practice2_pillars.yaml"));

// Figs 5.9/5.10: around the rectangle, GTG + AO hard switching chatters at p and the chatter is
// reported; follow-boundary gets round with a handful of switches.
TEST(Rectangle, HardSwitchChattersAndFollowBoundaryCuresIt) {
  const RunResult hard = run("rectangle.yaml", {"controller.kind=hard_switch"});
  EXPECT_GE(hard.chatter_episodes, 1);
  EXPECT_GT(hard.mode_switches, 50);
  EXPECT_GT(hard.first_chatter_time, 0.0);
  const RunResult hybrid = run("rectangle.yaml");
  EXPECT_EQ(hybrid.status, RunStatus::Reached);
  EXPECT_TRUE(used_follow_boundary(hybrid));
  EXPECT_LT(hybrid.mode_switches, 10);
  EXPECT_LT(hybrid.mode_switches * 10, hard.mode_switches);
  // The chatter happens before the rectangle: at p, in front of its near face (x = 1.0).
  ASSERT_FALSE(hard.transitions.empty());
  EXPECT_LT(hard.transition_x[static_cast<std::size_t>(hard.mode_switches) / 2], 1.0);
}

// The course's week-7 pocket: the QuickBot escapes the U and reaches (1.1, 1.1) within 30 s.
TEST(Week7Pocket, EscapedWithin30Seconds) {
  const RunResult r = run("week7_pocket.yaml");
  EXPECT_EQ(r.status, RunStatus::Reached);
  EXPECT_LE(r.sim_time, 30.0);
  EXPECT_TRUE(used_follow_boundary(r));
}

// Figs 5.15/5.16: the delivery follows the assembly line, then the warehouse wall.
TEST(FactoryDelivery, FollowsTheLineThenTheWall) {
  const RunResult r = run("factory_delivery.yaml");
  ASSERT_EQ(r.status, RunStatus::Reached);
  int follow_episodes = 0;
  for (const auto& t : r.transitions)
    if (r.mode_names[static_cast<std::size_t>(t.to)].rfind("follow_boundary", 0) == 0)
      ++follow_episodes;
  EXPECT_EQ(follow_episodes, 2);
  EXPECT_GT(time_in(r, "follow_boundary_cw"), 0.0);   // along the assembly line
  EXPECT_GT(time_in(r, "follow_boundary_ccw"), 0.0);  // down the wall to the doorway
}

// Practice 2: hard switching is bumpy (many switches); blending is smooth (no switching) but
// gives no guarantee: it stalls in front of the rectangle.
TEST(Practice2, HardSwitchingIsBumpyBlendingIsSmooth) {
  const RunResult hard = run("practice2_pillars.yaml", {"controller.kind=hard_switch"});
  const RunResult blend = run("practice2_pillars.yaml", {"controller.kind=blended"});
  EXPECT_EQ(blend.status, RunStatus::Reached);
  EXPECT_EQ(blend.mode_switches, 1);  // blended -> stop only
  EXPECT_GT(hard.mode_switches, 20);
  const RunResult blend_rect = run("rectangle.yaml", {"controller.kind=blended"});
  EXPECT_NE(blend_rect.status, RunStatus::Reached);
  EXPECT_FALSE(blend_rect.collided);
}

TEST(MultipleGoals, VisitedInOrder) {
  const RunResult r = run("factory_delivery.yaml", {"goals=[[2.0,3.4],[5.2,0.8]]"});
  EXPECT_EQ(r.goal_count, 2);
  EXPECT_EQ(r.goals_reached, 2);
  EXPECT_EQ(r.status, RunStatus::Reached);
}

// Same scenario and seed: the same trajectory, bit for bit; another seed with noise differs.
TEST(Determinism, SameSeedSameTrajectoryBitForBit) {
  const std::vector<std::string> noisy{"robot.sensors.noise=0.005"};
  const RunResult a = run("factory_delivery.yaml", noisy);
  const RunResult b = run("factory_delivery.yaml", noisy);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    ASSERT_EQ(a.trajectory[i].x, b.trajectory[i].x) << i;
    ASSERT_EQ(a.trajectory[i].y, b.trajectory[i].y) << i;
    ASSERT_EQ(a.trajectory[i].theta, b.trajectory[i].theta) << i;
  }
  const RunResult c = run("factory_delivery.yaml", {"robot.sensors.noise=0.005", "sim.seed=2"});
  EXPECT_NE(c.final_x, a.final_x);
}

TEST(Outcomes, StuckAndTimeoutAreReported) {
  const RunResult stuck = run("rectangle.yaml", {"controller.kind=blended"});
  EXPECT_EQ(stuck.status, RunStatus::Stuck);
  const RunResult timeout = run("factory_delivery.yaml", {"sim.t_max=5"});
  EXPECT_EQ(timeout.status, RunStatus::Timeout);
  EXPECT_NEAR(timeout.sim_time, 5.0, 1e-6);
}

// Liveness watches progress, not speed: a robot that crawls towards its goal, slower than
// sim.stuck_radius per sim.stuck_window, is not stuck (the Pioneer's arena at 0.05 m/s slows
// to 8 mm/s before its goal, eq. 5.19); one that sits still is.
TEST(Outcomes, CrawlingTowardsTheGoalIsNotStuck) {
  const RunResult crawl = run("coppeliasim_pioneer.yaml", {"controller.v0=0.05", "sim.t_max=800"});
  EXPECT_EQ(crawl.status, RunStatus::Reached) << crawl.stuck_cause;
  const std::string hall = "world: {bounds: [-1, -1, 3, 1]}\nrobot: {start: [0, 0, 0]}\n";
  const RunResult slow = simulate(load_scenario_text(
      hall + "goal: [0.8, 0]\ncontroller: {v0: 0.01}\nsim: {t_max: 400}\n", "slow.yaml"));
  EXPECT_EQ(slow.status, RunStatus::Reached) << slow.stuck_cause;
  // A cruise speed that rounds to nothing on the wheels: no move, no progress.
  const RunResult still = simulate(load_scenario_text(
      hall + "goal: [0.8, 0]\ncontroller: {v0: 1e-9}\nsim: {t_max: 400}\n", "still.yaml"));
  EXPECT_EQ(still.status, RunStatus::Stuck);
  EXPECT_EQ(still.stuck_cause, "no_progress");
}

// The run that once lied: a robot on a map without bounds, a wall across the map's whole height
// between it and its goal. Off the map is solid, so it cannot drive round the wall: the run is
// never `reached` (the grid optimum already said no path exists).
TEST(MapWithoutBounds, NoRobotDrivesRoundAWallOffTheMap) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("floornav_offmap_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "wall.map") << "type octile\nheight 6\nwidth 9\nmap\n"
                                     "....@....\n....@....\n....@....\n"
                                     "....@....\n....@....\n....@....\n";
  for (const char* kind : {"hybrid", "go_to_goal"}) {
    SCOPED_TRACE(kind);
    const std::string text = std::string("world: {map: wall.map, cell_size: 0.5}\n") +
                             "robot: {start: [0.75, 1.5, 0]}\ngoal: [3.75, 1.5]\n" +
                             "controller: {kind: " + kind + "}\nsim: {t_max: 60}\n";
    const Scenario s = load_scenario_text(text, dir / "offmap.yaml");
    const RunResult r = simulate(s);
    EXPECT_NE(r.status, RunStatus::Reached) << to_string(r.status);
    double lowest = 1e9, highest = -1e9;
    for (const TrajectorySample& p : r.trajectory) {
      lowest = std::min(lowest, p.y);
      highest = std::max(highest, p.y);
    }
    if (!r.trajectory.empty()) {
      EXPECT_GE(lowest, 0.0);   // never below the map
      EXPECT_LE(highest, 3.0);  // nor above it
    }
  }
  std::filesystem::remove_all(dir);
}
