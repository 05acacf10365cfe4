// The planning layer's pieces on hand-worked cases: the path follower's projection and
// lookahead, the progress checker, the rolling grid's evidence, decay and inflation, the
// planner's recovery and `stuck`, and DWA's objective and window.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "floornav/geometry/angle.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/nav/dwa_controller.hpp"
#include "floornav/nav/footprint_guard.hpp"
#include "floornav/nav/heading_tracker.hpp"
#include "floornav/nav/navigation_controller.hpp"
#include "floornav/nav/planned_path.hpp"
#include "floornav/nav/planner_controller.hpp"
#include "floornav/nav/progress_checker.hpp"
#include "floornav/nav/rolling_grid.hpp"
#include "floornav/nav/sampling_planner.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/validate.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

// --- PlannedPath: projection and lookahead ------------------------------------------------------

// An L: (0, 0) -> (4, 0) -> (4, 4), 8 m long.
PlannedPath l_path() {
  PlannedPath p;
  const std::vector<Vec2> pts{{0, 0}, {4, 0}, {4, 4}};
  p.assign(pts);
  return p;
}

TEST(PlannedPath, ProjectsOntoTheNearestSegmentAndCountsWhatIsLeft) {
  PlannedPath p = l_path();
  EXPECT_DOUBLE_EQ(p.length(), 8.0);
  EXPECT_NEAR(p.project(Vec2(1.0, 0.2), 10.0), 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(p.progress(), 1.0);
  EXPECT_DOUBLE_EQ(p.remaining(), 7.0);
  EXPECT_EQ(p.segment(), 0u);
  // Past the corner, on the second leg.
  EXPECT_NEAR(p.project(Vec2(4.3, 2.0), 10.0), 0.3, 1e-12);
  EXPECT_DOUBLE_EQ(p.progress(), 6.0);
  EXPECT_EQ(p.segment(), 1u);
}

TEST(PlannedPath, NeverProjectsBackwards) {
  PlannedPath p = l_path();
  p.project(Vec2(3.0, 0.0), 10.0);
  p.project(Vec2(0.5, 0.0), 10.0);  // the robot was pushed back: the projection stays
  EXPECT_DOUBLE_EQ(p.progress(), 3.0);
}

TEST(PlannedPath, LooksOnlyAsFarAheadAsAsked) {
  // A U whose far leg passes close to the start: with a short horizon the projection does not
  // jump to it.
  PlannedPath p;
  const std::vector<Vec2> pts{{0, 0}, {4, 0}, {4, 1}, {0, 1}};
  p.assign(pts);
  p.project(Vec2(0.5, 0.6), 2.0);
  EXPECT_EQ(p.segment(), 0u);
  EXPECT_DOUBLE_EQ(p.progress(), 0.5);
}

TEST(PlannedPath, SubgoalStopsAtTheCornerUntilTheRobotIsNearIt) {
  PlannedPath p = l_path();
  // 2.5 m along: 2 m ahead would be round the corner, but the corner is 1.5 m away (> 1).
  p.project(Vec2(2.5, 0.0), 10.0);
  const Vec2 a = p.subgoal(Vec2(2.5, 0.0), 2.0, 1.0);
  EXPECT_NEAR(a.x(), 4.0, 1e-12);
  EXPECT_NEAR(a.y(), 0.0, 1e-12);
  // 3.5 m along, 0.5 m from the corner: the subgoal goes round it, 2 m on (5.5 m along).
  p.project(Vec2(3.5, 0.1), 10.0);
  const Vec2 b = p.subgoal(Vec2(3.5, 0.1), 2.0, 1.0);
  EXPECT_NEAR(b.x(), 4.0, 1e-12);
  EXPECT_NEAR(b.y(), 1.5, 1e-12);
  // On a straight stretch: lookahead metres ahead; near the end: the end.
  p.project(Vec2(4.0, 1.0), 10.0);
  EXPECT_NEAR(p.subgoal(Vec2(4.0, 1.0), 2.0, 1.0).y(), 3.0, 1e-12);
  p.project(Vec2(4.0, 3.5), 10.0);
  EXPECT_NEAR(p.subgoal(Vec2(4.0, 3.5), 2.0, 1.0).y(), 4.0, 1e-12);
}

// --- ProgressChecker -----------------------------------------------------------------------------

TEST(ProgressChecker, StallIsTooLittleProgressWithinTheWindow) {
  ProgressChecker c(8.0, 0.5);
  c.reset(0.0, 10.0);
  EXPECT_FALSE(c.stalled(4.0, 9.7));  // 0.3 m: not yet progress, window not over
  EXPECT_TRUE(c.stalled(8.0, 9.6));   // 0.4 m in 8 s: a stall
  c.reset(8.0, 9.6);
  EXPECT_FALSE(c.stalled(9.0, 9.0));  // 0.6 m: progress, the window starts again at 9 s
  EXPECT_DOUBLE_EQ(c.anchor_time(), 9.0);
  EXPECT_DOUBLE_EQ(c.best(), 9.0);
  EXPECT_FALSE(c.stalled(16.9, 8.8));
  EXPECT_TRUE(c.stalled(17.0, 8.8));
  // Going backwards (a longer plan) is no progress either.
  c.reset(20.0, 5.0);
  EXPECT_FALSE(c.stalled(27.0, 6.5));
  EXPECT_TRUE(c.stalled(28.0, 6.5));
}

// --- RollingGrid: evidence, decay, memory, inflation ---------------------------------------------

// One sensor at (0.05, 0.05) looking along +x, 1 m range, in a grid of 0.1 m cells.
struct OneBeam {
  std::vector<RangeSensorSpec> sensors{RangeSensorSpec{{Vec2::Zero(), 0.0}, 0.0, 1.0, 0.0, 1}};
  std::vector<SensorBeam> beams{SensorBeam{Vec2(0.05, 0.05), Vec2(1.0, 0.0), 0.0}};
  void scan(RollingGrid& g, double range, double t) {
    const double r[] = {range};
    g.update(beams, r, sensors, 100.0, t);
  }
};

TEST(RollingGrid, AReturnMarksItsCellTheBeamClearsTheCellsBefore) {
  RollingGrid g(0.1, 40, 5.0, Vec2::Zero());
  OneBeam s;
  s.scan(g, 0.5, 0.0);  // return at x = 0.55: cell 5
  for (int x = 0; x < 5; ++x) EXPECT_EQ(g.evidence({x, 0}, 0.0), -1) << x;
  EXPECT_EQ(g.evidence({5, 0}, 0.0), 2);
  EXPECT_TRUE(g.occupied({5, 0}, 0.0));
  EXPECT_EQ(g.evidence({6, 0}, 0.0), 0) << "beyond the return: unknown";
  EXPECT_EQ(g.evidence({5, 1}, 0.0), 0);
  s.scan(g, 0.5, 0.1);  // seen again
  EXPECT_EQ(g.evidence({5, 0}, 0.1), 4);
  EXPECT_EQ(g.evidence({2, 0}, 0.1), -2);
  // The obstacle is gone: each scan through it takes one off; occupied while >= 2.
  s.scan(g, 1.0, 0.2);
  EXPECT_EQ(g.evidence({5, 0}, 0.2), 3);
  s.scan(g, 1.0, 0.3);
  EXPECT_EQ(g.evidence({5, 0}, 0.3), 2);
  EXPECT_TRUE(g.occupied({5, 0}, 0.3));
  s.scan(g, 1.0, 0.4);
  EXPECT_EQ(g.evidence({5, 0}, 0.4), 1);
  EXPECT_FALSE(g.occupied({5, 0}, 0.4));
  // A max-range reading marks nothing at its end.
  EXPECT_EQ(g.evidence({10, 0}, 0.4), 0);
  EXPECT_EQ(g.evidence({9, 0}, 0.4), -2) << "three clear beams: down to the floor, -2";
}

TEST(RollingGrid, UnseenCellsFadeOneStepPerDecayPeriod) {
  RollingGrid g(0.1, 40, 5.0, Vec2::Zero());
  OneBeam s;
  s.scan(g, 0.5, 0.0);
  s.scan(g, 0.5, 0.0);  // the same scan time twice: evidence 4, updated at t = 0
  EXPECT_EQ(g.evidence({5, 0}, 4.9), 4);
  EXPECT_EQ(g.evidence({5, 0}, 5.0), 3);
  EXPECT_EQ(g.evidence({5, 0}, 10.0), 2);
  EXPECT_TRUE(g.occupied({5, 0}, 14.9));
  EXPECT_EQ(g.evidence({5, 0}, 15.0), 1);
  EXPECT_FALSE(g.occupied({5, 0}, 15.0));
  EXPECT_EQ(g.evidence({2, 0}, 10.0), 0) << "free evidence fades too";
}

TEST(RollingGrid, RemembersTheExactReturnPoint) {
  RollingGrid g(0.1, 40, 5.0, Vec2::Zero());
  OneBeam s;
  s.scan(g, 0.47, 0.0);  // x = 0.52, in cell 5
  std::vector<Vec2> out(8);
  ASSERT_EQ(g.remembered_points(Vec2(0.05, 0.05), 0.6, 1.0, out), 1u);
  EXPECT_NEAR(out[0].x(), 0.52, 1e-6);
  EXPECT_NEAR(out[0].y(), 0.05, 1e-6);
  EXPECT_EQ(g.remembered_points(Vec2(0.05, 0.05), 0.4, 1.0, out), 0u) << "0.47 m away";
  EXPECT_EQ(g.remembered_points(Vec2(0.05, 0.05), 0.6, 20.0, out), 0u) << "faded";
}

TEST(RollingGrid, InflationBlocksCellsWhoseCentreIsNearAReturn) {
  RollingGrid g(0.1, 40, 5.0, Vec2::Zero());
  OneBeam s;
  s.scan(g, 0.5, 0.0);  // return at (0.55, 0.05)
  FreeRaster r;
  g.inflate(0.15, 0.0, r);
  ASSERT_EQ(r.width, 40);
  const GridCell o = g.origin();
  auto free_at = [&](int gx, int gy) { return r.is_free(gx - o.x, gy - o.y); };
  EXPECT_FALSE(free_at(5, 0));  // 0 m
  EXPECT_FALSE(free_at(4, 0));  // 0.1 m
  EXPECT_FALSE(free_at(6, 1));  // 0.141 m
  EXPECT_TRUE(free_at(3, 0));   // 0.2 m
  EXPECT_TRUE(free_at(5, 2));   // 0.2 m
  EXPECT_TRUE(free_at(2, 0)) << "cleared cells are free, not blocked";
}

TEST(RollingGrid, MovingTheWindowForgetsOnlyWhatLeavesIt) {
  RollingGrid g(0.1, 40, 5.0, Vec2::Zero());  // cells -20 .. 19
  OneBeam s;
  s.scan(g, 0.5, 0.0);
  g.follow(Vec2(0.5, 0.0));  // 5 cells: within a quarter window, nothing moves
  EXPECT_EQ(g.origin().x, -20);
  g.follow(Vec2(1.5, 0.0));  // 15 cells: the window recentres on cell 15 (origin -5)
  EXPECT_EQ(g.origin().x, -5);
  EXPECT_TRUE(g.occupied({5, 0}, 0.0)) << "still inside: kept";
  EXPECT_EQ(g.evidence({-10, 0}, 0.0), 0) << "outside: unknown";
  g.follow(Vec2(3.0, 0.0));  // origin 10: cell 5 left the window
  EXPECT_FALSE(g.in_window({5, 0}));
  g.follow(Vec2(0.0, 0.0));  // back: cell 5 is in the window again, but forgotten
  EXPECT_EQ(g.evidence({5, 0}, 0.0), 0);
}

// --- PlannerController: recovery and stuck -------------------------------------------------------

// A QuickBot-sized robot planning on a known, empty 4 x 4 m room; the observations are made
// by hand, so the robot can be held still to stall it.
struct PlannerRig {
  RobotSpec robot = find_robot_preset("quickbot")->robot;
  NavigationParams nav = find_robot_preset("quickbot")->navigation;
  std::shared_ptr<World> world;
  std::unique_ptr<Controller> c;

  explicit PlannerRig(WorldDesc desc = {}) {
    if (!desc.bounds) desc.bounds = Box2{Vec2(0, 0), Vec2(4, 4)};
    world = std::make_shared<World>(std::move(desc));
    ControllerConfig cfg;
    cfg.params = nav;
    cfg.planner.kind = PlannerKind::AStar;
    cfg.planner.progress_window = 2.0;
    cfg.planner.max_recoveries = 2;
    c = ControllerMaker().make(cfg, {robot, nav, "r", 0, world.get()});
  }
  Decision at(const Pose2& pose, double t, const Vec2& goal = Vec2(3.5, 2.0)) {
    Observation o;
    o.t = t;
    o.dt = 0.01;
    o.pose = pose;
    o.goal = goal;
    o.goal_count = 1;
    o.robot = &robot;
    o.params = &nav;
    return c->decide(o);
  }
  std::string mode(const Decision& d) const {
    return c->mode_names()[static_cast<std::size_t>(d.mode)];
  }
};

TEST(PlannerController, NamesTheAutomatonsModesAndItsOwn) {
  PlannerRig rig;
  const auto& m = rig.c->mode_names();
  ASSERT_GE(m.size(), 8u);
  EXPECT_EQ(m[0], "go_to_goal");
  EXPECT_EQ(m[m.size() - 3], "recovery_back_up");
  EXPECT_EQ(m[m.size() - 2], "recovery_turn");
  EXPECT_EQ(m[m.size() - 1], "stuck");
  const auto& g = rig.c->guard_names();
  EXPECT_EQ(g[g.size() - 3], "progress_stalled");
}

TEST(PlannerController, AStalledRobotBacksUpTurnsThenGivesUp) {
  PlannerRig rig;
  const Pose2 held{Vec2(0.5, 2.0), 0.0};
  Decision d = rig.at(held, 0.0);
  EXPECT_EQ(rig.mode(d), "go_to_goal");
  EXPECT_EQ(d.command.kind(), Command::Kind::Velocity);
  // Held still for the whole window: a stall, and the first recovery backs up at v0 / 2.
  for (double t = 0.01; t < 2.0; t += 0.01) d = rig.at(held, t);
  d = rig.at(held, 2.0);
  EXPECT_EQ(rig.mode(d), "recovery_back_up");
  EXPECT_EQ(d.command.kind(), Command::Kind::Unicycle);
  EXPECT_DOUBLE_EQ(d.command.unicycle_command().v, -0.5 * rig.nav.v0);
  EXPECT_DOUBLE_EQ(d.command.unicycle_command().omega, 0.0);
  EXPECT_EQ(rig.c->guard_names()[static_cast<std::size_t>(d.guard)], "progress_stalled");
  // Backed up by the body radius (0.075 m): it turns towards the new path (here ahead: it is
  // already facing it, so it goes straight back to following).
  d = rig.at({Vec2(0.42, 2.0), 0.0}, 2.5);
  EXPECT_NE(rig.mode(d), "recovery_back_up");
  EXPECT_NE(d.command.kind(), Command::Kind::Stuck);
  // Two more stalls: the second recovery, then (max_recoveries = 2) stuck.
  double t = 2.5;
  int recoveries = 1;
  while (d.command.kind() != Command::Kind::Stuck && t < 30.0) {
    t += 0.01;
    const std::string before = rig.mode(d);
    d = rig.at({Vec2(0.42, 2.0), 0.0}, t);
    if (rig.mode(d) == "recovery_back_up" && before != "recovery_back_up") ++recoveries;
  }
  EXPECT_EQ(d.command.kind(), Command::Kind::Stuck);
  EXPECT_EQ(rig.mode(d), "stuck");
  EXPECT_EQ(recoveries, 2);
  EXPECT_LT(t, 10.0) << "two windows and two short recoveries";
}

TEST(PlannerController, TurnsTowardsThePathAfterBackingUp) {
  PlannerRig rig;
  // Facing away from the goal, held: stall, back up, then turn left or right towards it.
  const Pose2 held{Vec2(0.5, 2.0), kPi};
  Decision d = rig.at(held, 0.0);
  for (double t = 0.01; t <= 2.0 + 1e-9; t += 0.01) d = rig.at(held, t);
  ASSERT_EQ(rig.mode(d), "recovery_back_up");
  d = rig.at({Vec2(0.6, 2.0), kPi}, 2.2);  // 0.1 m back (towards +x)
  EXPECT_EQ(rig.mode(d), "recovery_turn");
  const double w = d.command.unicycle_command().omega;
  EXPECT_NE(w, 0.0);
  EXPECT_DOUBLE_EQ(d.command.unicycle_command().v, 0.0);
}

TEST(PlannerController, NoPathOnTheKnownMapIsStuckAtOnce) {
  // The goal stands inside a closed square ring of walls.
  WorldDesc desc;
  desc.bounds = Box2{Vec2(0, 0), Vec2(4, 4)};
  desc.polygons.push_back({{2.5, 1.5}, {3.9, 1.5}, {3.9, 1.6}, {2.5, 1.6}});
  desc.polygons.push_back({{2.5, 2.4}, {3.9, 2.4}, {3.9, 2.5}, {2.5, 2.5}});
  desc.polygons.push_back({{2.5, 1.5}, {2.6, 1.5}, {2.6, 2.5}, {2.5, 2.5}});
  desc.polygons.push_back({{3.8, 1.5}, {3.9, 1.5}, {3.9, 2.5}, {3.8, 2.5}});
  PlannerRig rig(desc);
  const Decision d = rig.at({Vec2(0.5, 2.0), 0.0}, 0.0, Vec2(3.2, 2.0));
  EXPECT_EQ(d.command.kind(), Command::Kind::Stuck);
  EXPECT_EQ(rig.c->guard_names()[static_cast<std::size_t>(d.guard)], "no_path");
}

// The controller refuses a sample budget that rrt_connect_path would refuse, at construction:
// a plan made in the step loop never throws.
TEST(PlannerController, RefusesASampleBudgetAboveTheLimitWhenMade) {
  RobotSpec robot = find_robot_preset("quickbot")->robot;
  NavigationParams nav = find_robot_preset("quickbot")->navigation;
  WorldDesc desc;
  desc.bounds = Box2{Vec2(0, 0), Vec2(4, 4)};
  const World world(std::move(desc));
  ControllerConfig cfg;
  cfg.params = nav;
  cfg.planner.kind = PlannerKind::RrtConnect;
  cfg.planner.max_samples = kMaxRrtConnectSamples + 1;
  EXPECT_THROW(ControllerMaker().make(cfg, {robot, cfg.params, "r", 0, &world}),
               std::invalid_argument);
  // At the limit it is made, with whatever search is installed (a stand-in when this test binary
  // has no OMPL).
  const SampledPathSearch saved = rrt_connect_search();
  if (!saved)
    set_rrt_connect_search([](const FreeRaster&, GridCell, GridCell, std::uint64_t, int,
                              std::vector<Vec2>&) { return false; });
  cfg.planner.max_samples = kMaxRrtConnectSamples;
  EXPECT_NE(ControllerMaker().make(cfg, {robot, cfg.params, "r", 0, &world}), nullptr);
  set_rrt_connect_search(saved);
}

TEST(PlannerController, ReportsGoalReachedOnlyAtTheRealGoal) {
  PlannerRig rig;
  // Far from the goal, the subgoal is on the way; within epsilon of the goal: STOP.
  EXPECT_NE(rig.at({Vec2(0.5, 2.0), 0.0}, 0.0).command.kind(), Command::Kind::GoalReached);
  EXPECT_EQ(rig.at({Vec2(3.48, 2.0), 0.0}, 0.01).command.kind(), Command::Kind::GoalReached);
}

// --- DWA -----------------------------------------------------------------------------------------

TEST(Dwa, ObjectiveByHand) {
  DwaParams p;  // alpha 1, beta 0.4, gamma 0.3, max_clearance 1 m
  // Goal 90 degrees off at the end, 0.5 m driven before a collision, half speed:
  // 1 (1 - 0.5) + 0.4 (0.5 / 1) + 0.3 (0.5 / 1) = 0.5 + 0.2 + 0.15.
  EXPECT_NEAR(dwa_score(p, kPi / 2, 0.5, 0.5, 1.0), 0.85, 1e-12);
  // No obstacle on the arc scores the cap; facing the goal scores 1: 1 + 0.4 + 0.3.
  EXPECT_NEAR(dwa_score(p, 0.0, std::numeric_limits<double>::infinity(), 1.0, 1.0), 1.7, 1e-12);
  // Facing away: heading 0; dist beyond the cap is the cap; standing still: no velocity.
  EXPECT_NEAR(dwa_score(p, kPi, 2.0, 0.0, 1.0), 0.4, 1e-12);
  EXPECT_NEAR(dwa_score(p, -3.0, 0.3, 0.2, 1.0), dwa_score(p, 2.0 * kPi - 3.0, 0.3, 0.2, 1.0),
              1e-12);
}

Observation dwa_obs(const RobotSpec& robot, const NavigationParams& nav, const Pose2& pose,
                    const Vec2& goal, std::span<const Vec2> points) {
  Observation o;
  o.dt = 0.05;
  o.pose = pose;
  o.goal = goal;
  o.points = points;
  o.sensed = points;
  o.robot = &robot;
  o.params = &nav;
  return o;
}

TEST(Dwa, AcceleratesWithinTheWindowTowardsAGoalAhead) {
  RobotSpec robot = find_robot_preset("turtlebot3_burger")->robot;
  NavigationParams nav = find_robot_preset("turtlebot3_burger")->navigation;
  DwaController c(nav, DwaParams{}, robot);
  const Decision d = c.decide(dwa_obs(robot, nav, {Vec2::Zero(), 0.0}, Vec2(5, 0), {}));
  ASSERT_EQ(d.command.kind(), Command::Kind::Unicycle);
  // From rest, one step of 0.05 s at 2.5 m/s^2: at most 0.125 m/s, and straight ahead.
  EXPECT_NEAR(d.command.unicycle_command().v, 0.125, 1e-12);
  EXPECT_NEAR(d.command.unicycle_command().omega, 0.0, 1e-12);
  EXPECT_EQ(c.mode_names()[static_cast<std::size_t>(d.mode)], "dwa");
}

TEST(Dwa, NeverDrivesAtAWallItCannotStopBefore) {
  RobotSpec robot = find_robot_preset("turtlebot3_burger")->robot;
  NavigationParams nav = find_robot_preset("turtlebot3_burger")->navigation;
  DwaController c(nav, DwaParams{}, robot);
  // A wall of points 0.15 m ahead of the body, across the way to the goal.
  std::vector<Vec2> wall;
  for (double y = -1.0; y <= 1.0; y += 0.02) wall.emplace_back(0.105 + 0.15, y);
  for (int k = 0; k < 20; ++k) {
    const Decision d = c.decide(dwa_obs(robot, nav, {Vec2::Zero(), 0.0}, Vec2(5, 0), wall));
    const UnicycleCommand u = d.command.unicycle_command();
    // Whatever it chooses, driving it for the braking time keeps the body off the wall.
    const double t_brake = u.v / robot.max_acceleration;
    EXPECT_LT(u.v * t_brake, 0.15) << k;
  }
}

// The discs covering a footprint: one per width along its long side. A sliver's count is a large
// finite number, never an int that overflowed.
TEST(Dwa, FootprintDiscsAreOnePerWidthAlongTheLongSide) {
  const auto box = [](double length, double width) {
    return std::vector<Vec2>{{-length / 2, -width / 2},
                             {length / 2, -width / 2},
                             {length / 2, width / 2},
                             {-length / 2, width / 2}};
  };
  EXPECT_EQ(dwa_footprint_discs({}), 1.0);  // the body disc
  EXPECT_EQ(dwa_footprint_discs(box(0.5, 0.5)), 1.0);
  EXPECT_EQ(dwa_footprint_discs(box(0.5, 0.25)), 2.0);
  EXPECT_EQ(dwa_footprint_discs(box(0.25, 0.5)), 2.0);  // the long side along y
  EXPECT_EQ(dwa_footprint_discs(box(0.5, 0.3)), 2.0);   // 1.67: rounded up
  EXPECT_EQ(dwa_footprint_discs(box(1.0, 1e-12)), 1e9);
  EXPECT_EQ(dwa_footprint_discs(box(1e6, 0.0)), 1e15);  // a segment: a width of 1e-9
}

// A dwa robot's work per step is bounded before the controller is made: the footprint at the
// disc limit and the roll-outs at the check limit are accepted (and the controller is made),
// one more of either is refused naming the key.
TEST(Dwa, WorkPerStepIsBoundedByValidation) {
  const RobotPreset p = *find_robot_preset("quickbot");
  Scenario s;
  WorldDesc desc;
  desc.bounds = Box2{Vec2(-1, -1), Vec2(5, 3)};
  s.world = std::make_shared<const World>(std::move(desc));
  RobotTask& t = s.robots.emplace_back();
  t.robot = p.robot;
  t.controller.kind = "dwa";
  t.controller.params = p.navigation;
  t.start = {Vec2(0, 0), 0.0};
  t.goals = {Vec2(4, 1)};
  s.sim.dt = 0.01;
  // 64 x as long as wide, the length of the body's diameter.
  const double length = 2.0 * t.robot.body_radius, width = length / 64.0;
  t.robot.footprint = {{-length / 2, -width / 2},
                       {length / 2, -width / 2},
                       {length / 2, width / 2},
                       {-length / 2, width / 2}};
  DwaParams& d = t.controller.dwa;
  d.v_samples = 25;  // 25 x 25 x 25 poses x 64 discs = 10^6 checks: the limit
  d.omega_samples = 25;
  d.horizon = 2.5;
  d.sim_step = 0.1;
  EXPECT_NO_THROW(validate_scenario(s, "s.yaml"));
  EXPECT_NO_THROW(DwaController(t.controller.params, t.controller.dwa, t.robot));
  d.omega_samples = 26;
  try {
    validate_scenario(s, "s.yaml");
    ADD_FAILURE() << "26 x 25 x 25 x 64 checks a step were accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "controller.dwa");
    EXPECT_NE(e.detail.find("= 25 x 26 x 25 x 64 = 1.04e+06 footprint checks a step, more than "
                            "the 1e+06 allowed"),
              std::string::npos)
        << e.detail;
  }
  d.omega_samples = 25;
  const double thinner = length / 65.0;
  t.robot.footprint = {{-length / 2, -thinner / 2},
                       {length / 2, -thinner / 2},
                       {length / 2, thinner / 2},
                       {-length / 2, thinner / 2}};
  try {
    validate_scenario(s, "s.yaml");
    ADD_FAILURE() << "a footprint of 65 discs was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "robot.footprint");
    EXPECT_NE(e.detail.find("more than the 64 allowed"), std::string::npos) << e.detail;
  }
  // The controller refuses it too, made without validation (a library user's own scenario).
  EXPECT_THROW(DwaController(t.controller.params, t.controller.dwa, t.robot),
               std::invalid_argument);
  // Another controller kind does not cover the footprint with discs: the sliver is its business.
  t.controller.kind = "hybrid";
  EXPECT_NO_THROW(validate_scenario(s, "s.yaml"));
}

// --- PlannerController: the footprint guard ------------------------------------------------------

// A Jackal at (1, 2) facing +x in an empty, known 6 x 4 m room, its goal straight to its left
// (+y): the automaton's u points at +y and the heading PID turns the robot on the spot,
// counter-clockwise, at up to 10 rad/s. One point 0.026 m ahead of its front edge, beside the
// front-right corner (robot frame (0.28, -0.05)): a counter-clockwise turn on the spot swings that
// corner into it after acos(0.254 / 0.28443) - atan2(0.05, 0.28) = 0.4670 - 0.1767 = 0.29 rad.
struct GuardRig {
  RobotSpec robot = find_robot_preset("jackal")->robot;
  NavigationParams nav = find_robot_preset("jackal")->navigation;
  std::shared_ptr<World> world;
  std::unique_ptr<Controller> c;
  std::vector<Vec2> points{Vec2(1.28, 1.95)};
  PidState pid;  // the simulator's pipeline, for commands that are velocities

  explicit GuardRig(double horizon) {
    WorldDesc desc;
    desc.bounds = Box2{Vec2(-2, -1), Vec2(4, 5)};
    world = std::make_shared<World>(std::move(desc));
    ControllerConfig cfg;
    cfg.params = nav;
    cfg.planner.kind = PlannerKind::AStar;
    cfg.planner.guard_horizon = horizon;
    c = ControllerMaker().make(cfg, {robot, nav, "r", 0, world.get()});
  }
  // What the robot drives after deciding at `pose`: a velocity through the pipeline (as the
  // simulator does it), a unicycle as it is; saturated as the wheels would.
  UnicycleCommand drive(const Pose2& pose, double t) {
    Observation o;
    o.t = t;
    o.dt = 0.05;
    o.pose = pose;
    o.goal = Vec2(1.0, 3.5);
    o.goal_count = 1;
    o.points = points;
    o.robot = &robot;
    o.params = &nav;
    const Command cmd = c->decide(o).command;
    UnicycleCommand u = cmd.kind() == Command::Kind::Velocity
                            ? track_velocity(cmd.u(), pose.theta, nav.v0, nav.heading_pid, pid,
                                             o.dt, nav.slow_when_turning)
                            : cmd.unicycle_command();
    return wheels_to_unicycle(robot.drive, saturate_wheels(robot.drive, u));
  }
  double clearance(const Pose2& pose) const {
    const double c0 = std::cos(pose.theta), s0 = std::sin(pose.theta);
    std::vector<Vec2> local;
    for (const Vec2& q : points) {
      const Vec2 d = q - pose.position;
      local.emplace_back(c0 * d.x() + s0 * d.y(), -s0 * d.x() + c0 * d.y());
    }
    return footprint_clearance(robot.footprint, local);
  }
  // Two seconds of 20 Hz steps, integrated exactly (the unicycle's arc); the least clearance.
  double run() {
    Pose2 pose{Vec2(1.0, 2.0), 0.0};
    double least = clearance(pose);
    for (int k = 0; k < 40; ++k) {
      const UnicycleCommand u = drive(pose, 0.05 * k);
      const double th = pose.theta + u.omega * 0.05;
      if (std::abs(u.omega) > 1e-12)
        pose.position += Vec2(u.v / u.omega * (std::sin(th) - std::sin(pose.theta)),
                              -u.v / u.omega * (std::cos(th) - std::cos(pose.theta)));
      else
        pose.position += u.v * 0.05 * Vec2(std::cos(pose.theta), std::sin(pose.theta));
      pose.theta = th;
      least = std::min(least, clearance(pose));
    }
    return least;
  }
};

TEST(PlannerController, WithoutTheGuardTheTurnOnTheSpotSwingsACornerIntoThePoint) {
  GuardRig rig(0.0);
  EXPECT_NEAR(rig.clearance({Vec2(1.0, 2.0), 0.0}), 0.026, 1e-12);
  EXPECT_LE(rig.run(), 0.0) << "the corner reaches the point";
}

TEST(PlannerController, TheFootprintGuardNeverTurnsACornerIntoThePoint) {
  GuardRig rig(0.5);
  // The first command: not the fast counter-clockwise turn on the spot (contact 0.29 rad away),
  // and free of the point for most of the horizon at its own speed.
  const UnicycleCommand first = rig.drive({Vec2(1.0, 2.0), 0.0}, 0.0);
  const std::vector<Vec2> local{Vec2(0.28, -0.05)};
  EXPECT_EQ(time_to_contact(rig.robot.footprint, local, first.v, first.omega, 0.4, 0.0),
            std::numeric_limits<double>::infinity());
  // Two seconds of it, the robot moving as commanded: the rectangle never touches the point.
  GuardRig again(0.5);
  EXPECT_GT(again.run(), 0.0);
}

}  // namespace
}  // namespace floornav
