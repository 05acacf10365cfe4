// Social-navigation metrics and people at a density: path irregularity and time not moving on
// runs worked by hand, the fleet's step-weighted aggregate, the walkers of `random_people`
// (where they may stand and walk, the count the density asks for, the seed), and one case of the
// density sweep on factory-people's floor (scenarios/factory_density_template.yaml).
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "floornav/geometry/angle.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/scenario/random_people.hpp"
#include "floornav/scenario/simulate.hpp"

using namespace floornav;

namespace {

// A QuickBot alone in a 3 x 2 m room, facing `theta`, its goal 1 m along x.
Scenario lone_robot(const std::string& theta) {
  return load_scenario_text(
      "world: {bounds: [-1, -1, 2, 1]}\n"
      "robot: {start: [0, 0, " +
          theta + "]}\ngoal: [1, 0]\n",
      "lone.yaml");
}

World room_with_box() {  // 10 x 10 m, a 2 x 2 m box in the middle
  WorldDesc d;
  d.bounds = Box2{Vec2(0, 0), Vec2(10, 10)};
  d.polygons.push_back({Vec2(4, 4), Vec2(6, 4), Vec2(6, 6), Vec2(4, 6)});
  return World(d);
}

}  // namespace

// A robot that stands 2 s (200 steps of 0.01 s) facing its goal, then drives straight at it: it
// was not moving for exactly those 2 s, and its heading never left the line to the goal, so its
// path irregularity is 0.
TEST(SocialMetrics, AWaitIsTimeNotMovingAndAStraightRunIsRegular) {
  const Scenario s = lone_robot("0");
  Simulation sim = make_simulation(s);
  for (int k = 0; k < 200; ++k) ASSERT_TRUE(sim.step(Command::unicycle(0.0, 0.0)));
  EXPECT_EQ(sim.result().wait_time, 2.0);
  while (sim.step(Command::unicycle(0.1, 0.0))) {
  }
  const RunResult& r = sim.result();
  EXPECT_EQ(r.status, RunStatus::Reached);
  EXPECT_GT(r.path_length, 0.9);
  EXPECT_EQ(r.wait_time, 2.0);  // driving at 0.1 m/s is moving
  EXPECT_EQ(r.path_irregularity, 0.0);
  const auto j = summary_to_json(r);
  EXPECT_EQ(j["path_irregularity"].get<double>(), 0.0);
}

// Standing sideways to the goal, every step's heading is a quarter turn off the line to it: the
// mean is pi/2. Facing away, pi. Standing, the whole time is time not moving.
TEST(SocialMetrics, PathIrregularityIsTheMeanAngleOffTheLineToTheGoal) {
  const std::vector<std::pair<std::string, double>> cases{{"1.5707963267948966", kPi / 2},
                                                          {"-1.5707963267948966", kPi / 2},
                                                          {"3.141592653589793", kPi}};
  for (const auto& [theta, angle] : cases) {
    SCOPED_TRACE(theta);
    const Scenario s = lone_robot(theta);  // outlives the simulation
    Simulation sim = make_simulation(s);
    for (int k = 0; k < 100; ++k) ASSERT_TRUE(sim.step(Command::unicycle(0.0, 0.0)));
    EXPECT_NEAR(sim.result().path_irregularity, angle, 1e-12);
    EXPECT_EQ(sim.result().wait_time, 1.0);
  }
}

// The chapter's robot turning towards a goal behind it: irregular at first (it faces away), then
// regular; the mean lies strictly between 0 and pi.
TEST(SocialMetrics, TurningTowardsTheGoalIsPartlyIrregular) {
  const RunResult r = simulate(lone_robot("3.0"));
  EXPECT_EQ(r.status, RunStatus::Reached);
  EXPECT_GT(r.path_irregularity, 0.01);
  EXPECT_LT(r.path_irregularity, 3.0);
}

// A fleet's path irregularity is the mean over every robot step: each robot's weighted by its
// steps, (0.2 * 100 + 0.6 * 300) / 400 = 0.5, not the plain mean 0.4.
TEST(SocialMetrics, TheFleetWeighsEachRobotByItsSteps) {
  FleetResult f;
  f.scenario = "two";
  f.robots.resize(2);
  f.robots[0].scenario = "a";
  f.robots[0].steps = 100;
  f.robots[0].path_irregularity = 0.2;
  f.robots[0].wait_time = 1.5;
  f.robots[1].scenario = "b";
  f.robots[1].steps = 300;
  f.robots[1].path_irregularity = 0.6;
  f.robots[1].wait_time = 0.5;
  const auto j = fleet_summary_to_json(f);
  EXPECT_NEAR(j["fleet"]["path_irregularity"].get<double>(), 0.5, 1e-15);
  EXPECT_EQ(j["fleet"]["wait_time"].get<double>(), 2.0);
  EXPECT_EQ(j["robots"][1]["path_irregularity"].get<double>(), 0.6);
  // No robot step: 0, not NaN.
  FleetResult none;
  none.robots.resize(1);
  EXPECT_EQ(fleet_summary_to_json(none)["fleet"]["path_irregularity"].get<double>(), 0.0);
}

// 10 x 10 m less the 2 x 2 m box: 96 m² of free floor, on the 0.05 m lattice exactly.
TEST(RandomPeople, FreeFloorAreaWorkedByHand) {
  const World w = room_with_box();
  EXPECT_NEAR(free_floor_area(w, *w.bounds()), 96.0, 1e-9);
  EXPECT_NEAR(free_floor_area(w, Box2{Vec2(0, 0), Vec2(5, 5)}), 24.0, 1e-9);  // a quarter box
}

// 0.25 people per m² of 96 m²: 24 walkers, where a person may stand, apart, clear of the robot's
// start by the personal space, each on a route of straight legs that its body clears.
TEST(RandomPeople, PlacesTheDensityOnFreeFloorOnWalkableRoutes) {
  const World w = room_with_box();
  RobotTask robot;
  robot.start = {Vec2(1, 1), 0.0};
  robot.robot.body_radius = 0.075;
  const std::vector<RobotTask> robots{robot};
  const std::vector<PersonSpec> scripted{{"ann", Vec2(9, 9), {Vec2(8, 9)}}};
  RandomPeopleSpec spec;
  spec.density = 0.25;
  const RandomPeople placed = place_random_people(w, spec, robots, scripted, {}, 7);
  EXPECT_EQ(placed.asked, 24u);
  ASSERT_EQ(placed.people.size(), 24u);
  std::set<std::string> names;
  for (std::size_t a = 0; a < placed.people.size(); ++a) {
    const PersonSpec& p = placed.people[a];
    SCOPED_TRACE(p.name);
    names.insert(p.name);
    EXPECT_EQ(p.radius, 0.25);
    EXPECT_GE(p.speed, 0.8);
    EXPECT_LE(p.speed, 1.3);
    EXPECT_TRUE(p.cyclic);
    EXPECT_GE(w.clearance(p.start), p.radius + 0.1);
    EXPECT_GE((p.start - robot.start.position).norm() - 0.075 - p.radius, kPersonalSpace);
    EXPECT_GE((p.start - scripted[0].start).norm(), 2 * 0.25 + 0.1);
    for (std::size_t b = 0; b < a; ++b)
      EXPECT_GE((p.start - placed.people[b].start).norm(), 2 * 0.25 + 0.1);
    ASSERT_EQ(p.waypoints.size(), 3u);
    // Every leg, the closing one too, at 1 mm: the body never meets the world.
    for (std::size_t k = 0; k <= p.waypoints.size(); ++k) {
      const Vec2 a0 = k == 0 ? p.start : p.waypoints[k - 1];
      const Vec2 b0 = p.waypoints[k % p.waypoints.size()];
      const int n = static_cast<int>(std::ceil((b0 - a0).norm() / 0.001)) + 1;
      for (int i = 0; i <= n; ++i)
        ASSERT_GT(w.clearance(a0 + (b0 - a0) * (static_cast<double>(i) / n)), p.radius) << k;
    }
  }
  EXPECT_EQ(names.size(), 24u);
  EXPECT_EQ(names.count("walker0"), 1u);
}

// The same seed places the same people, bit for bit; another seed others. A floor too small for
// the density places fewer than asked (the loader turns that into an error).
TEST(RandomPeople, TheSeedDecidesAndAFullFloorIsReported) {
  const World w = room_with_box();
  RandomPeopleSpec spec;
  spec.density = 0.2;
  const RandomPeople a = place_random_people(w, spec, {}, {}, {}, 3);
  const RandomPeople b = place_random_people(w, spec, {}, {}, {}, 3);
  const RandomPeople c = place_random_people(w, spec, {}, {}, {}, 4);
  ASSERT_EQ(a.people.size(), b.people.size());
  for (std::size_t k = 0; k < a.people.size(); ++k) {
    EXPECT_EQ(a.people[k].start, b.people[k].start);
    EXPECT_EQ(a.people[k].waypoints, b.people[k].waypoints);
    EXPECT_EQ(a.people[k].speed, b.people[k].speed);
  }
  EXPECT_NE(a.people[0].start, c.people[0].start);
  spec.density = 2.0;  // 192 people of 0.25 m with 0.1 m between them: no room
  const RandomPeople full = place_random_people(w, spec, {}, {}, {}, 3);
  EXPECT_EQ(full.asked, 192u);
  EXPECT_LT(full.people.size(), full.asked);
  EXPECT_GT(full.people.size(), 50u);
}

// The scenario key: walkers after the scripted people, as many as the density asks, from
// sim.seed; the written configuration lists them as people (it loads back the same).
TEST(RandomPeople, TheScenarioKeyAddsWalkers) {
  const std::string yaml =
      "world: {bounds: [0, 0, 10, 10], obstacles: [{polygon: [[4, 4], [6, 4], [6, 6], [4, 6]]}]}\n"
      "robot: {start: [1, 1, 0]}\ngoal: [9, 1]\n"
      "people: [{name: ann, start: [9, 9], waypoints: [[8, 9]]}]\n"
      "random_people: {density: 0.1, speed: [1.0, 1.1], waypoints: 2}\n"
      "sim: {seed: 5}\n";
  const Scenario s = load_scenario_text(yaml, "walkers.yaml");
  ASSERT_EQ(s.crowd.people.size(), 1u + 10u);  // round(0.1 * 96)
  EXPECT_EQ(s.crowd.people[0].name, "ann");
  EXPECT_EQ(s.crowd.people[1].name, "walker0");
  for (std::size_t k = 1; k < s.crowd.people.size(); ++k) {
    EXPECT_EQ(s.crowd.people[k].waypoints.size(), 2u);
    EXPECT_GE(s.crowd.people[k].speed, 1.0);
    EXPECT_LE(s.crowd.people[k].speed, 1.1);
  }
  const Scenario again = load_scenario_text(yaml, "walkers.yaml");
  EXPECT_EQ(again.crowd.people.back().start, s.crowd.people.back().start);
}

// One case of the density sweep (scripts/benchmarks.sh density): factory-people's floor with
// 0.3 people per m² (42 walkers), its six robots and two forklifts, the first 40 s. No robot
// touches a person, a forklift, another robot or the world; the metrics are there and sane.
TEST(PeopleDensity, FactoryFloorAtPointThreeHasNoContact) {
  const std::vector<std::string> sets{"random_people.density=0.3", "sim.t_max=40", "sim.seed=2"};
  const Scenario s = load_scenario_file(
      std::string(FLOORNAV_SCENARIO_DIR) + "/factory_density_template.yaml", sets);
  ASSERT_EQ(s.crowd.people.size(), 42u);
  const FleetResult f = simulate_fleet(s);
  const CrowdMetrics& m = f.crowd.metrics;
  EXPECT_EQ(m.person_contacts, 0);
  EXPECT_EQ(m.forklift_contacts, 0);
  EXPECT_TRUE(f.collisions.empty());
  EXPECT_EQ(f.collided, 0);
  EXPECT_GT(m.min_person_gap, 0.0);
  // People come near the robots at this density, and those entries are counted and timed.
  EXPECT_GT(m.intrusions, 0);
  EXPECT_GT(m.intrusion_time, 0.0);
  double robot_time = 0.0, waiting = 0.0;
  for (const RunResult& r : f.robots) {
    SCOPED_TRACE(r.scenario);
    EXPECT_GE(r.path_irregularity, 0.0);
    EXPECT_LE(r.path_irregularity, kPi);
    EXPECT_GE(r.wait_time, 0.0);
    EXPECT_LE(r.wait_time, r.sim_time + 1e-9);
    EXPECT_GT(r.path_length, 1.0);  // every robot got going
    robot_time += r.sim_time;
    waiting += r.wait_time;
  }
  EXPECT_LT(waiting, robot_time);
  const auto j = fleet_summary_to_json(f);
  const double irregularity = j["fleet"]["path_irregularity"].get<double>();
  EXPECT_GT(irregularity, 0.0);  // they turn round machines, people and each other
  EXPECT_LT(irregularity, kPi / 2);
  EXPECT_EQ(j["crowd"]["people"], 42);
}
