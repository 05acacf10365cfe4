// Fleets: robots that sense each other, robot-robot collisions, the fleet summary, and the
// guarantees a fleet keeps (a fleet of one is a lone robot; any thread count gives the same
// result; the neighbour grid finds exactly who is near).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/io/trajectory_csv.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sensing/sensor_fans.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/robot_neighbour_grid.hpp"
#include "floornav/sim/simulation.hpp"

using namespace floornav;

namespace {

Scenario scenario_file(const std::string& name, std::vector<std::string> sets = {}) {
  return load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + name, sets);
}

double time_in(const RunResult& r, const std::string& mode) {
  for (std::size_t i = 0; i < r.mode_names.size(); ++i)
    if (r.mode_names[i] == mode) return r.mode_time[i];
  return 0.0;
}

// Two robots facing each other along y = 0, `gap` metres apart between their bodies.
std::string head_on_yaml(const std::string& kind, double gap, const char* safety = "off") {
  const double x = 0.075 + 0.5 * gap;  // QuickBot body radius 0.075 m
  return "world: {bounds: [-2, -1, 2, 1]}\n"
         "robots:\n"
         "  - {name: a, start: [" +
         std::to_string(-x) + ", 0, 0], goal: [1.5, 0]}\n" + "  - {name: b, start: [" +
         std::to_string(x) + ", 0, 3.141592653589793], goal: [-1.5, 0]}\n" +
         "controller: {kind: " + kind + ", safety: " + safety + ", robot_avoidance: none}\n";
}

// A ray meets another robot's body as it meets a circular obstacle: a beam along +x from the
// origin hits a disc of radius 0.1 m centred at (1, 0) at 0.9 m (worked by hand).
TEST(FleetSensing, ABeamStopsAtAnotherRobotsBody) {
  const World empty(WorldDesc{});
  RangeSensorSpec beam;
  beam.max_range = 2.0;
  const std::vector<RangeSensorSpec> sensors{beam};
  std::vector<SensorBeam> beams(1);
  compute_sensor_beams(Pose2{}, sensors, beams);
  std::vector<double> ranges(1);
  Rng rng(1);
  const std::vector<Circle> others{{Vec2(1.0, 0.0), 0.1}, {Vec2(1.5, 0.0), 0.1}};
  sense_ranges(empty, beams, sensors, 0.0, rng, ranges, {}, others);
  EXPECT_DOUBLE_EQ(ranges[0], 0.9);
  // Off the beam's line by more than the radius: nothing seen.
  const std::vector<Circle> beside{{Vec2(1.0, 0.25), 0.1}};
  sense_ranges(empty, beams, sensors, 0.0, rng, ranges, {}, beside);
  EXPECT_DOUBLE_EQ(ranges[0], 2.0);
}

// A lidar fan tests each other robot's body only against the beams near it: the ranges are the
// all-pairs ones, bit for bit, for full and partial fans, bodies straddling the +-pi seam, bodies
// around the origin and bodies far beyond the range.
TEST(FleetSensing, FanAgainstOtherBodiesEqualsEveryBeamAgainstEveryBody) {
  Rng rng(11);
  WorldDesc desc;
  desc.bounds = Box2{Vec2(-6, -6), Vec2(6, 6)};
  desc.circles.push_back({Vec2(1.5, 0.5), 0.4});
  const World world(desc);
  for (int trial = 0; trial < 300; ++trial) {
    const int beams = std::vector<int>{16, 45, 180, 360, 720}[static_cast<std::size_t>(trial % 5)];
    const double fov = trial % 3 == 0 ? 2.0 * kPi : rng.uniform(0.5, 6.0);
    const Pose2 robot{Vec2(rng.uniform(-2, 2), rng.uniform(-2, 2)), rng.uniform(-kPi, kPi)};
    const auto sensors = make_lidar(beams, fov, 0.05, rng.uniform(0.5, 4.0), {Vec2(0.03, 0), 0});
    std::vector<Circle> others;
    const int n_others = static_cast<int>(rng.uniform(1, 30));
    for (int k = 0; k < n_others; ++k) {
      const double a = rng.uniform(-kPi, kPi), d = rng.uniform(0.0, 5.0);
      // Some bodies exactly behind the robot (the seam of the wrapped beam angles).
      const double ang = k % 7 == 0 ? robot.theta + kPi : a;
      others.push_back(
          {robot.position + d * Vec2(std::cos(ang), std::sin(ang)), rng.uniform(0.01, 0.5)});
    }
    std::vector<SensorBeam> b(sensors.size());
    compute_sensor_beams(robot, sensors, b);
    std::vector<double> fan(sensors.size()), each(sensors.size());
    Rng unused(1);
    sense_ranges(world, b, sensors, 0.0, unused, fan, {}, others);
    for (std::size_t k = 0; k < sensors.size(); ++k)  // one sensor at a time: no fan
      sense_ranges(world, std::span(b).subspan(k, 1), std::span(sensors).subspan(k, 1), 0.0, unused,
                   std::span(each).subspan(k, 1), {}, others);
    for (std::size_t k = 0; k < sensors.size(); ++k)
      ASSERT_EQ(fan[k], each[k]) << "trial " << trial << " beam " << k;
  }
}

// A lidar of at most a half turn passes over bodies behind its centre line without testing its
// beams: bodies just behind the line through the origin (less than a radius beyond it, so the
// fan's edge beams graze or cut them, and just more), near and far, for 180-degree lidars whose
// edge beams lie along that line: the ranges are the all-pairs ones, bit for bit.
TEST(FleetSensing, BodiesBehindAHalfTurnLidarAreSkippedOnlyWhenNoBeamMeetsThem) {
  Rng rng(12);
  WorldDesc desc;
  desc.bounds = Box2{Vec2(-20, -20), Vec2(20, 20)};
  const World world(desc);
  int seen = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int beams = trial % 2 == 0 ? 181 : 180;
    const double fov = trial % 3 == 2 ? rng.uniform(0.5, kPi) : kPi;
    const Pose2 robot{Vec2(rng.uniform(-2, 2), rng.uniform(-2, 2)), rng.uniform(-kPi, kPi)};
    const double range = 8.0;
    const auto sensors = make_lidar(beams, fov, 0.0, range, {Vec2(0.1, 0), 0});
    std::vector<SensorBeam> b(sensors.size());
    compute_sensor_beams(robot, sensors, b);
    const Vec2 o = b[0].origin;
    const Vec2 c(std::cos(robot.theta), std::sin(robot.theta)), side(-c.y(), c.x());
    std::vector<Circle> others;
    for (int k = 0; k < 30; ++k) {
      const double r = rng.uniform(0.05, 0.4);
      // Behind the line by r less up to half a radius, or by r plus a little (1e-12 to 1e-2 m).
      const double behind =
          k % 2 == 0 ? r * rng.uniform(0.5, 1.0) : r + std::pow(10.0, rng.uniform(-12.0, -2.0));
      others.push_back({o - behind * c + rng.uniform(-range, range) * side, r});
    }
    std::vector<double> fan(sensors.size()), each(sensors.size());
    Rng unused(1);
    sense_ranges(world, b, sensors, 0.0, unused, fan, {}, others);
    for (std::size_t k = 0; k < sensors.size(); ++k)
      sense_ranges(world, std::span(b).subspan(k, 1), std::span(sensors).subspan(k, 1), 0.0, unused,
                   std::span(each).subspan(k, 1), {}, others);
    for (std::size_t k = 0; k < sensors.size(); ++k) {
      ASSERT_EQ(fan[k], each[k]) << "trial " << trial << " beam " << k;
      if (each[k] < range) ++seen;
    }
  }
  // The edge beams of the 180-degree fans do meet the bodies less than a radius behind.
  EXPECT_GT(seen, 100);
}

// A lidar's beams are turned one from the next rather than computed with a sine and cosine each:
// within 1e-13 of the exact beams, for full and partial fans and any robot heading.
TEST(FleetSensing, LidarBeamsTurnedFromTheFirstStayOnTheExactDirections) {
  Rng rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = std::vector<int>{16, 180, 360, 720}[static_cast<std::size_t>(trial % 4)];
    const double fov = trial % 2 == 0 ? 2.0 * kPi : rng.uniform(0.5, 6.0);
    const auto sensors = make_lidar(n, fov, 0.1, 3.5, {Vec2(0.05, 0.01), rng.uniform(-3, 3)});
    const Pose2 robot{Vec2(rng.uniform(-5, 5), rng.uniform(-5, 5)), rng.uniform(-10, 10)};
    std::vector<SensorBeam> beams(sensors.size());
    compute_sensor_beams(robot, sensors, beams);
    for (std::size_t k = 0; k < sensors.size(); ++k) {
      const Pose2 exact = robot.compose(sensors[k].mount);
      const double heading = wrap_angle(exact.theta);
      EXPECT_NEAR(beams[k].dir.x(), std::cos(heading), 1e-13) << trial << " " << k;
      EXPECT_NEAR(beams[k].dir.y(), std::sin(heading), 1e-13) << trial << " " << k;
      EXPECT_NEAR(wrap_angle(beams[k].theta - heading), 0.0, 1e-13) << trial << " " << k;
      EXPECT_TRUE(beams[k].theta > -kPi && beams[k].theta <= kPi);
      EXPECT_NEAR((beams[k].origin - exact.position).norm(), 0.0, 1e-14);
    }
  }
}

// A fleet of one is the lone robot, bit for bit.
TEST(Fleet, AFleetOfOneRunsExactlyAsALoneRobot) {
  const Scenario s = scenario_file("factory_delivery.yaml");
  const RunResult lone = simulate(s);
  const FleetResult fleet = simulate_fleet(s);
  ASSERT_EQ(fleet.robots.size(), 1u);
  const RunResult& r = fleet.robots[0];
  EXPECT_EQ(r.status, lone.status);
  EXPECT_EQ(r.steps, lone.steps);
  EXPECT_EQ(r.path_length, lone.path_length);
  EXPECT_EQ(r.min_clearance, lone.min_clearance);
  ASSERT_EQ(r.trajectory.size(), lone.trajectory.size());
  for (std::size_t k = 0; k < r.trajectory.size(); ++k) {
    ASSERT_EQ(r.trajectory[k].x, lone.trajectory[k].x) << k;
    ASSERT_EQ(r.trajectory[k].y, lone.trajectory[k].y) << k;
    ASSERT_EQ(r.trajectory[k].theta, lone.trajectory[k].theta) << k;
  }
}

// Robots of one model read one copy of the body, sensors and controller parameters (a fleet step's
// working set); a robot that differs in any of them keeps its own.
TEST(Fleet, RobotsOfOneModelShareOneCopyOfItAndOthersKeepTheirOwn) {
  Scenario s = scenario_file("fleet_crossing.yaml");
  ASSERT_EQ(s.robots.size(), 4u);
  s.robots[3].robot.sensors[0].max_range += 0.01;  // another sensor
  s.robots[2].controller.params.v0 *= 0.99;        // another cruise speed
  const FleetSimulation fleet = make_fleet_simulation(s);
  EXPECT_EQ(&fleet.robot(0).robot(), &fleet.robot(1).robot());
  EXPECT_EQ(&fleet.robot(0).robot(), &fleet.robot(2).robot());
  EXPECT_NE(&fleet.robot(0).robot(), &fleet.robot(3).robot());
  EXPECT_EQ(fleet.robot(3).robot(), s.robots[3].robot);
  EXPECT_EQ(&fleet.robot(0).params(), &fleet.robot(1).params());
  EXPECT_NE(&fleet.robot(0).params(), &fleet.robot(2).params());
  EXPECT_EQ(fleet.robot(2).params().v0, s.robots[2].controller.params.v0);
  EXPECT_EQ(&fleet.robot(0).params(), &fleet.robot(3).params());
}

// Four robots meet in the middle of a hall and go round each other; everyone arrives and nobody
// touches, as shipped (the planner stack) and with the chapter's automaton alone under the layer,
// where a roundabout emerges from the clockwise boundary following.
TEST(Fleet, FourRobotsCrossingAHallGoRoundEachOther) {
  const FleetResult shipped = simulate_fleet(scenario_file("fleet_crossing.yaml"));
  EXPECT_EQ(shipped.status, RunStatus::Reached);
  EXPECT_EQ(shipped.deliveries, 4);
  EXPECT_TRUE(shipped.collisions.empty());
  const FleetResult f =
      simulate_fleet(scenario_file("fleet_crossing.yaml", {"controller.planner.kind=none"}));
  ASSERT_EQ(f.robots.size(), 4u);
  EXPECT_EQ(f.status, RunStatus::Reached);
  EXPECT_EQ(f.reached, 4);
  EXPECT_EQ(f.collided, 0);
  EXPECT_TRUE(f.collisions.empty());
  EXPECT_EQ(f.deliveries, 4);
  EXPECT_GT(f.min_clearance, 0.0);
  // The robots came within sensing range of each other: the clearance counts them.
  EXPECT_LT(f.min_clearance, 0.12);
  for (const RunResult& r : f.robots) {
    EXPECT_GT(time_in(r, "follow_boundary_cw") + time_in(r, "follow_boundary_ccw"), 0.0)
        << r.scenario << " never went round anyone";
  }
}

// Six robots on three-stop routes through a store room, passing in aisles and round parked
// robots: all 18 deliveries, no contact (the scenario as shipped, with the ORCA layer).
TEST(Fleet, SixRobotsDeliverThroughTheAislesWithoutContact) {
  const FleetResult f = simulate_fleet(scenario_file("fleet_aisles.yaml"));
  EXPECT_EQ(f.status, RunStatus::Reached);
  EXPECT_EQ(f.deliveries, 18);
  EXPECT_EQ(f.delivery_count, 18);
  EXPECT_EQ(f.collided, 0);
  EXPECT_GT(f.min_clearance, 0.0);
}

// The chapter's automaton alone in the same aisles, over start headings of the first robot turned
// by 0 to 18 mrad: the ring sees every robot, so no run has a contact; whether all 18 deliveries
// are made is left to chance (a robot may circle a shelf, docs/SCENARIOS.md "Known limits"), and
// what is not a delivery is a timeout or a stuck run that names its cause, never a collision.
TEST(Fleet, TheAutomatonAloneInTheAislesNeverTouches) {
  for (int k = 0; k < 4; ++k) {
    Scenario s = scenario_file("fleet_aisles.yaml", {"controller.robot_avoidance=none"});
    s.robots[0].start.theta += 0.006 * k;
    const FleetResult f = simulate_fleet(s);
    EXPECT_EQ(f.collided, 0) << k;
    EXPECT_TRUE(f.collisions.empty()) << k;
    EXPECT_GT(f.min_clearance, 0.0) << k;
    EXPECT_NE(f.status, RunStatus::Collision) << k;
    for (const RunResult& r : f.robots)
      EXPECT_TRUE(r.status != RunStatus::Stuck || !r.stuck_cause.empty()) << k;
    EXPECT_GE(f.deliveries, 15) << k;
  }
}

// Go-to-goal ignores what it senses: two robots driving at each other (the safety layer off) touch,
// both runs end as collisions, and the pair is logged once.
TEST(Fleet, RobotsThatIgnoreEachOtherCollideAndThePairIsLoggedOnce) {
  const Scenario s = load_scenario_text(head_on_yaml("go_to_goal", 0.5), "head_on.yaml");
  const FleetResult f = simulate_fleet(s);
  EXPECT_EQ(f.status, RunStatus::Collision);
  EXPECT_EQ(f.collided, 2);
  ASSERT_EQ(f.collisions.size(), 1u);
  EXPECT_EQ(f.collisions[0].robot, 0);
  EXPECT_EQ(f.collisions[0].other, 1);
  EXPECT_LE(f.min_clearance, 0.0);
  // They meet in the middle, each having driven about half the gap.
  for (const RunResult& r : f.robots) {
    EXPECT_TRUE(r.collided);
    EXPECT_NEAR(r.path_length, 0.25, 0.02);
  }
  EXPECT_NEAR(f.robots[0].final_x, -f.robots[1].final_x, 1e-9);
}

// The hybrid automaton, head on, sees the other robot and gets out of its way.
TEST(Fleet, HybridRobotsHeadOnPassEachOther) {
  const Scenario s = load_scenario_text(head_on_yaml("hybrid", 0.5), "head_on.yaml");
  const FleetResult f = simulate_fleet(s);
  EXPECT_EQ(f.collided, 0);
  EXPECT_EQ(f.reached, 2);
}

// A parked robot is an obstacle; with park_finished off it leaves the floor. Robot b's goal is
// on robot a's straight line and b gets there first.
TEST(Fleet, ParkedRobotsAreObstaclesUnlessTheyLeave) {
  const std::string yaml =
      "world: {bounds: [-1, -1, 3, 1]}\n"
      "robots:\n"
      "  - {name: a, start: [-0.8, 0, 0], goal: [2.5, 0]}\n"
      "  - {name: b, start: [1.2, 0.5, -1.5707963], goal: [1.2, 0]}\n";
  const FleetResult parked = simulate_fleet(load_scenario_text(yaml, "parked.yaml"));
  const FleetResult gone = simulate_fleet(
      load_scenario_text(yaml, "gone.yaml", std::vector<std::string>{"sim.park_finished=false"}));
  ASSERT_EQ(parked.reached, 2);
  ASSERT_EQ(gone.reached, 2);
  EXPECT_GT(time_in(parked.robots[0], "follow_boundary_cw") +
                time_in(parked.robots[0], "follow_boundary_ccw"),
            0.0);
  EXPECT_EQ(time_in(gone.robots[0], "follow_boundary_cw") +
                time_in(gone.robots[0], "follow_boundary_ccw"),
            0.0);
  EXPECT_LT(gone.robots[0].path_length, parked.robots[0].path_length);
}

// A random fleet of 60 noisy robots (72-beam rings, enough work for threads): one thread and
// three threads give the same bits.
// QuickBots (5 IR) on a lattice 1 m apart in a hall, each bound for the opposite corner, with
// the fleet defaults (ORCA, the safety layer) unless `extra` changes them.
Scenario quickbot_lattice(int robots, const std::string& extra = "") {
  std::string yaml = "world: {bounds: [0, 0, 20, 20]}\nrobot: {preset: quickbot}\n" + extra +
                     "sim: {t_max: 20}\nrobots:\n";
  for (int i = 0; i < robots; ++i) {
    const double x = 0.5 + (i % 19) * 1.0, y = 0.5 + (i / 19) * 1.0;
    yaml += "  - {start: [" + std::to_string(x) + ", " + std::to_string(y) + ", 0], goal: [" +
            std::to_string(20.0 - x) + ", " + std::to_string(20.0 - y) + "]}\n";
  }
  return load_scenario_text(yaml, "lattice.yaml");
}

TEST(Fleet, ThreadsFollowTheWorkOfAStep) {
  // 100 QuickBots with ORCA and the safety layer pay for a second thread (BM_Fleet_Circle/100,
  // BM_Fleet_QuickBotWarehouse/100); 50 do not, nor 100 with their 5 rays alone.
  EXPECT_EQ(make_fleet_simulation(quickbot_lattice(100)).threads_for(2), 2u);
  EXPECT_EQ(make_fleet_simulation(quickbot_lattice(50)).threads_for(2), 1u);
  const std::string bare = "controller: {robot_avoidance: none, safety: off}\n";
  EXPECT_EQ(make_fleet_simulation(quickbot_lattice(100, bare)).threads_for(2), 1u);
  EXPECT_EQ(make_fleet_simulation(quickbot_lattice(100)).threads_for(1), 1u);
}

TEST(Fleet, AnyNumberOfThreadsGivesTheSameResult) {
  std::string yaml =
      "world: {bounds: [0, 0, 8, 8], obstacles: [{circle: {center: [4, 4], radius: 0.5}}]}\n"
      "robot: {preset: quickbot, sensors: {noise: 0.003, lidar: {beams: 72, fov: 6.283185307, "
      "min_range: 0.02, max_range: 0.3}}}\n"
      "sim: {t_max: 20}\n"
      "robots:\n";
  Rng rng(7);
  for (int i = 0; i < 60; ++i) {
    const double x = 0.4 + (i % 8) * 1.0, y = 0.4 + (i / 8) * 1.0;
    if (std::hypot(x - 4, y - 4) < 0.8) continue;
    yaml += "  - {start: [" + std::to_string(x) + ", " + std::to_string(y) + ", " +
            std::to_string(rng.uniform(-3.0, 3.0)) + "], goal: [" + std::to_string(8.0 - x) + ", " +
            std::to_string(8.0 - y) + "]}\n";
  }
  const Scenario s = load_scenario_text(yaml, "random.yaml");
  FleetSimulation one = make_fleet_simulation(s), three = make_fleet_simulation(s);
  // 60 x (72 rays, and what ORCA and the safety layer add): three threads' worth of work.
  ASSERT_EQ(three.threads_for(3), 3u);
  one.run(1);
  three.run(3);
  const FleetResult a = one.result(), b = three.result();
  ASSERT_EQ(a.robots.size(), b.robots.size());
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.collisions.size(), b.collisions.size());
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    EXPECT_EQ(a.robots[i].status, b.robots[i].status) << i;
    EXPECT_EQ(a.robots[i].steps, b.robots[i].steps) << i;
    EXPECT_EQ(a.robots[i].final_x, b.robots[i].final_x) << i;
    EXPECT_EQ(a.robots[i].final_y, b.robots[i].final_y) << i;
    EXPECT_EQ(a.robots[i].min_clearance, b.robots[i].min_clearance) << i;
  }
  EXPECT_EQ(fleet_summary_to_json(a).dump(), fleet_summary_to_json(b).dump());
}

// Lidar robots (fans cast with per-thread marks) on two threads: the same bits as on one.
TEST(Fleet, LidarFleetOnTwoThreadsGivesTheSameResult) {
  std::string yaml =
      "world: {bounds: [0, 0, 6, 6], obstacles: [{circle: {center: [3, 3], radius: 0.4}}]}\n"
      "robot: {preset: turtlebot3_burger}\n"
      "sim: {t_max: 3}\n"
      "robots:\n";
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j) {
      if (i == 2 && j == 2) continue;
      const double x = 0.6 + 1.2 * i, y = 0.6 + 1.2 * j;
      yaml += "  - {start: [" + std::to_string(x) + ", " + std::to_string(y) + ", 0.3], goal: [" +
              std::to_string(6.0 - x) + ", " + std::to_string(6.0 - y) + "]}\n";
    }
  const Scenario s = load_scenario_text(yaml, "lidars.yaml");
  FleetSimulation one = make_fleet_simulation(s), two = make_fleet_simulation(s);
  ASSERT_EQ(two.threads_for(2), 2u);
  one.run(1);
  two.run(2);
  EXPECT_EQ(fleet_summary_to_json(one.result()).dump(), fleet_summary_to_json(two.result()).dump());
}

// run_steps measures each robot's contacts at the start of its next step (on threads, robots
// stepped in chunks): the same bits as step() after step(), on one thread or two, for any way of
// cutting the run into run_steps calls. A crowded hall: half the robots ignore the others
// (go_to_goal), so pairs touch and end; some hit walls and pillars; finished robots leave the floor
// (park_finished off), so who is present changes while robots still move.
TEST(Fleet, ContactsCollisionsAndLeavingRobotsOnTwoThreadsGiveTheSameBitsAsStep) {
  std::string yaml =
      "world: {bounds: [0, 0, 6, 6], obstacles: [{circle: {center: [3, 3], radius: 0.5}},"
      " {circle: {center: [1.5, 4.5], radius: 0.2}}]}\n"
      "robot: {preset: quickbot, sensors: {lidar: {beams: 60, fov: 6.283185307, "
      "min_range: 0.02, max_range: 0.4}}}\n"
      "sim: {t_max: 30, park_finished: false}\n"
      "controller: {safety: off, robot_avoidance: none}\n"
      "robots:\n";
  Rng rng(11);
  int n = 0;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) {
      const double x = 0.3 + 0.6 * i, y = 0.3 + 0.6 * j;
      if (std::hypot(x - 3, y - 3) < 0.8 || std::hypot(x - 1.5, y - 4.5) < 0.4) continue;
      double gx = 0, gy = 0;
      do {
        gx = rng.uniform(0.3, 5.7), gy = rng.uniform(0.3, 5.7);
      } while (std::hypot(gx - 3, gy - 3) < 0.7 || std::hypot(gx - 1.5, gy - 4.5) < 0.4);
      yaml += "  - {start: [" + std::to_string(x) + ", " + std::to_string(y) + ", " +
              std::to_string(rng.uniform(-3.0, 3.0)) + "], goal: [" + std::to_string(gx) + ", " +
              std::to_string(gy) + "]" + (n % 2 ? ", controller: {kind: go_to_goal}" : "") + "}\n";
      ++n;
    }
  const Scenario s = load_scenario_text(yaml, "crowd.yaml");
  FleetSimulation serial = make_fleet_simulation(s), whole = make_fleet_simulation(s),
                  pieces = make_fleet_simulation(s), one = make_fleet_simulation(s);
  ASSERT_EQ(whole.threads_for(2), 2u);
  while (serial.step()) {
  }
  whole.run(2);
  for (long long k = 1; !pieces.finished(); k = k % 7 + 1) pieces.run_steps(k, 2);
  for (long long k = 1; !one.finished(); k = k % 5 + 1) one.run_steps(k, 1);
  const FleetResult a = serial.result(), b = whole.result(), c = pieces.result(), d = one.result();
  // The scenario does what it is meant to: contacts, world collisions, robots that finish.
  int pairs = 0, walls = 0;
  for (const FleetCollision& col : a.collisions) (col.other >= 0 ? pairs : walls) += 1;
  EXPECT_GT(pairs, 3);
  EXPECT_GT(walls, 0);
  EXPECT_GT(a.reached, 5);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_EQ(a.steps, c.steps);
  const std::string json = fleet_summary_to_json(a).dump();
  EXPECT_EQ(json, fleet_summary_to_json(b).dump());
  EXPECT_EQ(json, fleet_summary_to_json(c).dump());
  EXPECT_EQ(json, fleet_summary_to_json(d).dump());
  ASSERT_EQ(a.collisions.size(), b.collisions.size());
  for (std::size_t k = 0; k < a.collisions.size(); ++k) {
    EXPECT_EQ(a.collisions[k].time, b.collisions[k].time) << k;
    EXPECT_EQ(a.collisions[k].robot, b.collisions[k].robot) << k;
    EXPECT_EQ(a.collisions[k].other, b.collisions[k].other) << k;
  }
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    EXPECT_EQ(a.robots[i].min_clearance, b.robots[i].min_clearance) << i;
    EXPECT_EQ(a.robots[i].min_clearance, c.robots[i].min_clearance) << i;
    EXPECT_EQ(a.robots[i].min_clearance, d.robots[i].min_clearance) << i;
    EXPECT_EQ(a.robots[i].final_x, c.robots[i].final_x) << i;
    EXPECT_EQ(a.robots[i].final_x, d.robots[i].final_x) << i;
    EXPECT_EQ(a.robots[i].final_theta, c.robots[i].final_theta) << i;
  }
}

// The neighbour grid returns every robot within the radius (and maybe a few more), for robots
// inside and outside its box.
TEST(RobotNeighbourGrid, FindsEveryRobotWithinTheRadius) {
  Rng rng(3);
  std::vector<Vec2> pts(500);
  std::vector<std::uint8_t> present(pts.size(), 1);
  for (auto& p : pts) p = Vec2(rng.uniform(-2.0, 12.0), rng.uniform(-2.0, 12.0));
  present[7] = 0;
  RobotNeighbourGrid grid;
  grid.reset(Box2{Vec2(0, 0), Vec2(10, 10)}, 0.7, pts.size());
  grid.build(pts, present);
  for (int q = 0; q < 200; ++q) {
    const Vec2 c(rng.uniform(-3.0, 13.0), rng.uniform(-3.0, 13.0));
    const double radius = rng.uniform(0.1, 2.0);
    std::set<std::size_t> found;
    grid.for_each_near(c, radius, [&](std::size_t j) { EXPECT_TRUE(found.insert(j).second); });
    for (std::size_t j = 0; j < pts.size(); ++j) {
      const bool near = (pts[j] - c).norm() <= radius;
      if (j == 7) {
        EXPECT_FALSE(found.count(j)) << "an absent robot was returned";
      } else if (near) {
        EXPECT_TRUE(found.count(j)) << "robot " << j << " missed";
      }
    }
  }
}

// refile moves robots between cells in place; the grid must be the one build makes, items in the
// same order (a robot's neighbours are visited in that order), whether a few robots changed cell
// (moved in place, to near and far cells, out of the box) or many (the counting sort again).
TEST(RobotNeighbourGrid, RefileFilesTheRobotsAsBuildWould) {
  Rng rng(11);
  const Box2 box{Vec2(0, 0), Vec2(10, 8)};
  std::vector<Vec2> pts(400);
  std::vector<std::uint8_t> present(pts.size(), 1);
  for (auto& p : pts) p = Vec2(rng.uniform(-1.0, 11.0), rng.uniform(-1.0, 9.0));
  for (std::size_t i = 0; i < pts.size(); i += 9) present[i] = 0;
  RobotNeighbourGrid grid, fresh;
  grid.reset(box, 0.5, pts.size());
  fresh.reset(box, 0.5, pts.size());
  grid.build(pts, present);
  const auto visits = [&](const RobotNeighbourGrid& g, const Vec2& c, double r) {
    std::vector<std::size_t> v;
    g.for_each_near(c, r, [&](std::size_t j) { v.push_back(j); });
    return v;
  };
  std::vector<std::uint32_t> cells(pts.size());
  for (int round = 0; round < 60; ++round) {
    const bool many = round % 4 == 3;  // moves costing more than the counting sort: rebuilt
    for (std::size_t i = 0; i < pts.size(); ++i) {
      if (rng.uniform(0.0, 1.0) < (many ? 0.5 : 0.02)) {
        pts[i] = rng.uniform(0.0, 1.0) < 0.7
                     ? pts[i] + Vec2(rng.uniform(-0.6, 0.6), rng.uniform(-0.6, 0.6))
                     : Vec2(rng.uniform(-2.0, 12.0), rng.uniform(-2.0, 10.0));
      }
      cells[i] = grid.cell_index(pts[i]);
    }
    grid.refile(cells, present);
    fresh.build(pts, present);
    const double h = grid.cell_size();
    for (double y = -0.5 * h; y < 8.0 + h; y += h)
      for (double x = -0.5 * h; x < 10.0 + h; x += h)
        ASSERT_EQ(visits(grid, Vec2(x, y), 0.0), visits(fresh, Vec2(x, y), 0.0))
            << "round " << round << ", the cell at (" << x << ", " << y << ")";
    ASSERT_EQ(visits(grid, Vec2(5, 4), 20.0), visits(fresh, Vec2(5, 4), 20.0)) << round;
  }
}

TEST(FleetSummary, ListsTheFleetTheCollisionsAndEachRobot) {
  const Scenario s = load_scenario_text(head_on_yaml("go_to_goal", 0.5), "head_on.yaml");
  const FleetResult f = simulate_fleet(s);
  const auto j = fleet_summary_to_json(f);
  EXPECT_EQ(j["status"], "collision");
  EXPECT_EQ(j["collided"], true);
  EXPECT_EQ(j["fleet"]["robots"], 2);
  EXPECT_EQ(j["fleet"]["robot_collisions"], 1);
  EXPECT_EQ(j["fleet"]["world_collisions"], 0);
  EXPECT_EQ(j["collisions"][0]["robot"], "a");
  EXPECT_EQ(j["collisions"][0]["other"], "b");
  ASSERT_EQ(j["robots"].size(), 2u);
  EXPECT_EQ(j["robots"][1]["scenario"], "b");
  EXPECT_EQ(j["robots"][1]["status"], "collision");
  const std::string csv = trajectory_to_csv(f);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t,x,y,theta,v,omega,w_left,w_right,mode,robot");
  EXPECT_NE(csv.find(",go_to_goal,b\n"), std::string::npos);
}

// A big fleet's CSV is handed out in pieces of about 1 MiB, never the whole file at once; the
// pieces make the same text, row for row.
TEST(FleetSummary, TheCsvComesInPiecesOfAboutAMegabyte) {
  FleetResult f;
  for (int k = 0; k < 3; ++k) {
    RunResult r;
    r.scenario = std::string(1, 'r');
    r.scenario += std::to_string(k);
    r.mode_names = {"go_to_goal"};
    for (int i = 0; i < 20000; ++i)
      r.trajectory.push_back({i * 0.01, 1.0 / (i + 3), 2.0 / (i + 7), 0.5, 0.1, 0.2, 3.0, 4.0, 0});
    f.robots.push_back(std::move(r));
  }
  std::vector<std::size_t> sizes;
  std::string text;
  trajectory_csv_pieces(f, [&](std::string_view piece) {
    sizes.push_back(piece.size());
    text.append(piece);
  });
  ASSERT_GE(sizes.size(), 3u);
  for (std::size_t size : sizes) EXPECT_LE(size, (1u << 20) + 256u);
  EXPECT_EQ(text, trajectory_to_csv(f));
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1 + 3 * 20000);
  EXPECT_EQ(text.substr(text.size() - 4), ",r2\n");
}

// Scenario errors name the robot: its index in the list and the key.
TEST(FleetScenario, ErrorsNameTheRobotAndTheKey) {
  const std::string base = "world: {bounds: [0, 0, 4, 4]}\n";
  auto error_of = [&](const std::string& yaml) {
    try {
      load_scenario_text(base + yaml, "fleet.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("robots: []\n").find("robots: expected a list of robots"), std::string::npos);
  EXPECT_NE(error_of("robots:\n  - {start: [1, 1, 0], goal: [2, 2]}\n"
                     "  - {start: [1.1, 1, 0], goal: [3, 3]}\n")
                .find("robots[1].start: touches robot 0"),
            std::string::npos);
  EXPECT_NE(error_of("robots:\n  - {start: [1, 1, 0], goal: [2, 2]}\n"
                     "  - {start: [5, 1, 0], goal: [3, 3]}\n")
                .find("robots[1].start"),
            std::string::npos);
  EXPECT_NE(error_of("robots:\n  - {start: [1, 1, 0], goal: [2, 9]}\n").find("robots[0].goal"),
            std::string::npos);
  EXPECT_NE(error_of("robots:\n  - {name: x, start: [1, 1, 0], goal: [2, 2]}\n"
                     "  - {name: x, start: [3, 1, 0], goal: [3, 3]}\n")
                .find("'x' names two robots"),
            std::string::npos);
  EXPECT_NE(error_of("goal: [1, 1]\nrobots:\n  - {start: [1, 1, 0], goal: [2, 2]}\n")
                .find("each robot has its own goal"),
            std::string::npos);
  EXPECT_NE(error_of("robot: {start: [1, 1, 0]}\nrobots:\n  - {start: [1, 1, 0], goal: [2, 2]}\n")
                .find("robot.start"),
            std::string::npos);
  EXPECT_NE(error_of("robots:\n  - {start: [1, 1, 0], goal: [2, 2], colour: red}\n")
                .find("robots[0].colour"),
            std::string::npos);
  EXPECT_NE(error_of("robots:\n  - {start: [1, 1, 0], goal: [2, 2], controller: {kind: fast}}\n")
                .find("robots[0].controller.kind"),
            std::string::npos);
}

// --set reaches into the list as errors name its entries: robots[1].start, robots[0].goal
// (replacing that robot's goals), a whole entry; a missing entry is one clear error.
TEST(FleetScenario, SetOverridesIndexTheRobotsList) {
  const std::string file = std::string(FLOORNAV_SCENARIO_DIR) + "/fleet_crossing.yaml";
  const Scenario s = load_scenario_file(
      file, std::vector<std::string>{
                "robots[1].start=[1.0, -0.2, 3.0]", "robots[0].goals=[[1, 1], [1.2, 0.1]]",
                "robots[3]={name: last, start: [0.1, 1.2, -1.5], goal: [0, 0]}"});
  EXPECT_EQ(s.robots[1].start.position, Vec2(1.0, -0.2));
  EXPECT_EQ(s.robots[1].start.theta, 3.0);
  ASSERT_EQ(s.robots[0].goals.size(), 2u);
  EXPECT_EQ(s.robots[0].goals[1], Vec2(1.2, 0.1));
  EXPECT_EQ(s.robots[3].name, "last");
  EXPECT_EQ(s.robots[2].name, "north");  // untouched
  auto error_of = [&](const std::string& set) {
    try {
      load_scenario_file(file, std::vector<std::string>{set});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("robots[4].start=[0, 0, 0]").find("'robots' has no entry [4] (it has 4)"),
            std::string::npos);
  EXPECT_NE(error_of("robots[-1].start=[0, 0, 0]").find("a list index is a number in brackets"),
            std::string::npos);
  EXPECT_NE(error_of("robots[0].start=[9, 9, 0]").find("--set robots[0].start=[9, 9, 0]"),
            std::string::npos);  // the bad value is blamed on the --set
}

// Shared robot defaults, per-robot controllers on top of the shared controller section.
TEST(FleetScenario, SharedRobotAndControllerDefaultsAreOverriddenPerRobot) {
  const Scenario s = load_scenario_text(
      "world: {bounds: [0, 0, 4, 4]}\n"
      "robot: {preset: khepera3, sensors: {noise: 0.01}}\n"
      "controller: {kind: blended, v0: 0.05}\n"
      "robots:\n"
      "  - {start: [1, 1, 0], goal: [2, 2]}\n"
      "  - {start: [3, 1, 0], goal: [3, 3], preset: quickbot, controller: {kind: hybrid}}\n",
      "fleet.yaml");
  ASSERT_EQ(s.robots.size(), 2u);
  EXPECT_EQ(s.robots[0].name, "robot0");
  EXPECT_EQ(s.robots[0].robot.preset, "khepera3");
  EXPECT_EQ(s.robots[1].robot.preset, "quickbot");
  EXPECT_EQ(s.robots[0].robot.sensor_noise, 0.01);
  EXPECT_EQ(s.robots[1].robot.sensor_noise, 0.01);
  EXPECT_EQ(s.robots[0].controller.kind, "blended");
  EXPECT_EQ(s.robots[1].controller.kind, "hybrid");
  EXPECT_EQ(s.robots[0].controller.params.v0, 0.05);
  EXPECT_EQ(s.robots[1].controller.params.v0, 0.05);
}

}  // namespace
