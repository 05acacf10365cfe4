// People and forklifts (sim/crowd.hpp, sim/social_force.hpp, geometry/oriented_box.hpp): the
// social force terms on values worked by hand, the forklift's footprint and route, what the robots
// sense of them, contacts and their metrics, the HuNavSim loader, determinism, and the factory
// floor's outcome.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sensing/sensor_fans.hpp"
#include "floornav/sim/crowd.hpp"
#include "floornav/sim/social_force.hpp"

using namespace floornav;

namespace {

const SocialForceParams kParams{};

// No robots near.
struct NoRobots {
  std::vector<Vec2> p, v;
  std::vector<double> r;
  std::vector<std::uint8_t> present;
  RobotBodies bodies() const { return {p, v, r, present}; }
};

// One robot standing at `at`.
struct OneRobot {
  std::vector<Vec2> p, v{Vec2::Zero()};
  std::vector<double> r{0.075};
  std::vector<std::uint8_t> present{1};
  explicit OneRobot(const Vec2& at) : p{at} {}
  RobotBodies bodies() const { return {p, v, r, present}; }
};

World room(double w, double h) {
  WorldDesc d;
  d.bounds = Box2{Vec2(0, 0), Vec2(w, h)};
  return World(d);
}

}  // namespace

// Driving term: standing, wanting 1.2 m/s along x with tau 0.5 s: (1.2 - 0) / 0.5 = 2.4 m/s^2.
TEST(SocialForce, DrivingTermWorkedByHand) {
  const Vec2 f = driving_force(Vec2::Zero(), Vec2(1, 0), 1.2, kParams);
  EXPECT_DOUBLE_EQ(f.x(), 2.4);
  EXPECT_DOUBLE_EQ(f.y(), 0.0);
  // At the desired velocity there is nothing to correct.
  EXPECT_EQ(driving_force(Vec2(1.2, 0), Vec2(1, 0), 1.2, kParams), Vec2::Zero());
}

// The other person stands still (s = 0): the ellipse is a circle, b = |r|, and the force is
// V0 / sigma exp(-|r| / sigma) along r: at 0.6 m, 7 e^-2 = 0.947347. One walking at 0.5 m/s
// straight at the person from 1 m (its 2 s step reaches the person, b = 0) pushes with the full
// 7 m/s^2; one walking away (s = 1, |r - s e| = 2, b = sqrt(2)) only with
// 7 e^(-sqrt(2)/0.3) 3 (1 + 1) / (4 sqrt 2) = 0.0666 (0.2497 if it stood).
TEST(SocialForce, RepulsionOfTheEllipseWorkedByHand) {
  Vec2 f = person_repulsion(Vec2(0.6, 0), Vec2::Zero(), kParams);
  EXPECT_NEAR(f.x(), 7.0 * std::exp(-2.0), 1e-12);
  EXPECT_NEAR(f.y(), 0.0, 1e-12);
  f = person_repulsion(Vec2(1, 0), Vec2(0.5, 0), kParams);
  EXPECT_NEAR(f.x(), 7.0, 1e-12);
  f = person_repulsion(Vec2(1, 0), Vec2(-0.5, 0), kParams);
  const double b = std::sqrt(2.0);
  EXPECT_NEAR(f.x(), 7.0 * std::exp(-b / 0.3) * 3.0 * 2.0 / (4.0 * b), 1e-12);
  EXPECT_NEAR(f.x(), 0.0666, 1e-4);
  EXPECT_LT(f.x(), person_repulsion(Vec2(1, 0), Vec2::Zero(), kParams).x());
  // Not pulled: the force always has a component away from the other.
  for (double a = -3.0; a < 3.0; a += 0.5) {
    const Vec2 r(std::cos(a), std::sin(a));
    EXPECT_GT(person_repulsion(r, Vec2(0.4, 0.3), kParams).dot(r), 0.0) << a;
  }
}

// Walls: U0 / R exp(-d / R) = 50 e^-1 = 18.394 at 0.2 m; the field of view halves what comes
// from behind (source behind: e . (-f) = -1 < cos 100 deg).
TEST(SocialForce, WallAndFieldOfViewWorkedByHand) {
  const Vec2 f = wall_repulsion(0.2, Vec2(0, 1), kParams);
  EXPECT_NEAR(f.y(), 50.0 * std::exp(-1.0), 1e-12);
  EXPECT_EQ(f.x(), 0.0);
  EXPECT_EQ(sight_weight(Vec2(1, 0), Vec2(-1, 0), kParams), 1.0);  // source ahead
  EXPECT_EQ(sight_weight(Vec2(1, 0), Vec2(1, 0), kParams), 0.5);   // source behind
  EXPECT_EQ(sight_weight(Vec2(1, 0), Vec2(0, 1), kParams), 1.0);   // beside: within 100 deg
}

// A 2 x 1 m footprint: distances to its boundary and rays into it, turned and not.
TEST(OrientedBox, DistancesAndRaysWorkedByHand) {
  const OrientedBox b = OrientedBox::make(Vec2(0, 0), Vec2(2, 1), 0.0);
  EXPECT_DOUBLE_EQ(signed_distance(b, Vec2(2, 0)), 1.0);
  EXPECT_DOUBLE_EQ(signed_distance(b, Vec2(0, 0)), -0.5);
  EXPECT_NEAR(signed_distance(b, Vec2(4, 4.5)), 5.0, 1e-12);  // from the corner (1, 0.5)
  EXPECT_DOUBLE_EQ(*intersect_ray(b, Vec2(-3, 0), Vec2(1, 0)), 2.0);
  EXPECT_DOUBLE_EQ(*intersect_ray(b, Vec2(0, 0), Vec2(1, 0)), 0.0);  // from inside
  EXPECT_FALSE(intersect_ray(b, Vec2(-3, 0), Vec2(-1, 0)));          // away from it
  EXPECT_FALSE(intersect_ray(b, Vec2(-3, 0.6), Vec2(1, 0)));         // beside it
  const OrientedBox turned = OrientedBox::make(Vec2(0, 0), Vec2(2, 1), kPi / 2);
  EXPECT_NEAR(*intersect_ray(turned, Vec2(-3, 0), Vec2(1, 0)), 2.5, 1e-12);
  EXPECT_NEAR(signed_distance(turned, Vec2(0, 2)), 1.0, 1e-12);
}

// Range sensors see forklifts: a single beam stops at the box; a lidar's fan gives the same
// ranges as its beams one at a time, with and without people (discs) on it.
TEST(CrowdSensing, BeamsStopAtForkliftsAndFansAgreeWithSingleBeams) {
  const World empty(WorldDesc{});
  const auto sensors = make_lidar(180, 2.0 * kPi, 0.05, 4.0, Pose2{});
  std::vector<SensorBeam> beams(sensors.size());
  compute_sensor_beams(Pose2{Vec2(0, 0), 0.3}, sensors, beams);
  const std::vector<OrientedBox> boxes{OrientedBox::make(Vec2(2, 0), Vec2(1.8, 0.9), 0.4),
                                       OrientedBox::make(Vec2(-1, 2), Vec2(1.8, 0.9), -1.0),
                                       OrientedBox::make(Vec2(9, 9), Vec2(1.8, 0.9), 0.0)};
  const std::vector<Circle> people{{Vec2(0, -1.5), 0.25}};
  std::vector<double> fan(sensors.size()), one(sensors.size());
  Rng rng(1);
  sense_ranges(empty, beams, sensors, 0.0, rng, fan, {}, people, boxes);
  for (std::size_t k = 0; k < sensors.size(); ++k)
    sense_ranges(empty, std::span(beams).subspan(k, 1), std::span(sensors).subspan(k, 1), 0.0, rng,
                 std::span(one).subspan(k, 1), {}, people, boxes);
  int hits = 0;
  for (std::size_t k = 0; k < sensors.size(); ++k) {
    ASSERT_EQ(fan[k], one[k]) << k;
    hits += fan[k] < 4.0;
  }
  EXPECT_GT(hits, 20);
  // The beam along +x from the origin meets the first box's near face.
  const std::vector<RangeSensorSpec> ahead{RangeSensorSpec{Pose2{}, 0.02, 4.0, 0.0, 1}};
  std::vector<SensorBeam> b(1);
  compute_sensor_beams(Pose2{}, ahead, b);
  std::vector<double> r(1);
  const std::vector<OrientedBox> square{OrientedBox::make(Vec2(2, 0), Vec2(1.0, 1.0), 0.0)};
  sense_ranges(empty, b, ahead, 0.0, rng, r, {}, {}, square);
  EXPECT_DOUBLE_EQ(r[0], 1.5);
}

// A person alone walks to its waypoint (reached within 0.3 m) and stops there (not cyclic),
// coasting at most v0 tau = 0.6 m on; one that meets a robot standing near its line goes round it
// without touching. (Exactly on the line, the model's forces cancel and it stands in front of the
// robot: the social force model has no way round a head-on block.)
TEST(Crowd, APersonWalksToItsWaypointRoundARobot) {
  const World w = room(6, 3);
  CrowdSpec spec;
  spec.people.push_back({"p", Vec2(0.5, 1.5), {Vec2(5.0, 1.5)}, 1.2, 0.25, 0.3, false});
  NoRobots none;
  Crowd alone(spec, w, 0, true);
  for (int k = 0; k < 1000; ++k) alone.step(0.01 * k, 0.01, none.bodies());
  EXPECT_LT((alone.people()[0].center - Vec2(5.0, 1.5)).norm(), 0.9);
  EXPECT_EQ(alone.result().people[0].waypoints_reached, 1);
  EXPECT_GT(alone.result().people[0].path_length, 4.5 - 0.3);
  EXPECT_LT(alone.result().people[0].path_length, 4.5 + 0.6);

  OneRobot robot(Vec2(2.75, 1.45));
  Crowd round(spec, w, 1, true);
  std::vector<CrowdContact> contacts;
  for (int k = 0; k < 1000; ++k) {
    round.step(0.01 * k, 0.01, robot.bodies());
    round.check(0.01, robot.bodies(), contacts);
  }
  EXPECT_TRUE(contacts.empty());
  const CrowdMetrics& m = round.result().metrics;
  EXPECT_EQ(m.person_contacts, 0);
  EXPECT_GT(m.min_person_gap, 0.0);
  EXPECT_LT(m.min_person_gap, kPersonalSpace);  // it passed close: one intrusion
  EXPECT_EQ(m.intrusions, 1);
  EXPECT_LT((round.people()[0].center - Vec2(5.0, 1.5)).norm(), 0.9);
  EXPECT_EQ(round.result().people[0].waypoints_reached, 1);
}

// A forklift drives its route at its speed (1 m/s: 2 m in 2 s), stops while a robot stands in
// the metre ahead of it, turns on the spot at a corner (pi/2 at 1 rad/s) before driving on.
TEST(Crowd, ForkliftsDriveTheirRouteStopForBodiesAheadAndTurnAtCorners) {
  const World w = room(10, 10);
  CrowdSpec spec;
  spec.forklifts.push_back(
      {"f", {Vec2(1, 1), Vec2(6, 1), Vec2(6, 8)}, 1.0, Vec2(1.8, 0.9), 1.0, false});
  NoRobots none;
  Crowd c(spec, w, 0, false);
  for (int k = 0; k < 200; ++k) c.step(0.01 * k, 0.01, none.bodies());
  EXPECT_NEAR(c.forklifts()[0].center.x(), 3.0, 1e-9);
  EXPECT_NEAR(c.forklifts()[0].center.y(), 1.0, 1e-12);
  // To the corner (3 m more), then the turn: about 1.57 s on the spot.
  for (int k = 0; k < 300; ++k) c.step(0.01 * k, 0.01, none.bodies());
  EXPECT_NEAR(c.forklifts()[0].center.x(), 6.0, 1e-9);
  for (int k = 0; k < 100; ++k) c.step(0.01 * k, 0.01, none.bodies());
  EXPECT_NEAR(c.forklifts()[0].center.y(), 1.0, 1e-12);  // still turning
  EXPECT_GT(c.forklifts()[0].axis.y(), 0.5);
  for (int k = 0; k < 160; ++k) c.step(0.01 * k, 0.01, none.bodies());
  EXPECT_GT(c.forklifts()[0].center.y(), 1.0);  // driving north
  EXPECT_NEAR(c.forklifts()[0].axis.y(), 1.0, 1e-12);

  // A robot 1.3 m ahead of the centre: 0.4 m beyond the front, within the zone.
  OneRobot robot(Vec2(2.3, 1.0));
  Crowd held(spec, w, 1, false);
  for (int k = 0; k < 300; ++k) held.step(0.01 * k, 0.01, robot.bodies());
  EXPECT_LT(held.forklifts()[0].center.x(), 2.3 - 0.9 - 0.075 - 0.0);
  EXPECT_GT(held.result().forklifts[0].still_time, 1.5);
  EXPECT_GT(held.result().metrics.forklift_stopped_time, 1.5);
}

namespace {

// A QuickBot driving straight (go_to_goal) down a dead-end corridor where a person stands.
std::string corridor_yaml(const std::string& extra) {
  return "world: {bounds: [0, 0, 3, 0.7]}\n"
         "robots:\n"
         "  - {name: bot, start: [0.3, 0.35, 0], goal: [2.9, 0.35]}\n"
         "controller: {kind: go_to_goal, safety: off}\n"
         "sim: {t_max: 40}\n" +
         extra;
}

}  // namespace

// A robot that drives into a person cornered at the end of a corridor: its run ends as a
// collision of kind person, counted once in the crowd's metrics and the summary.
TEST(CrowdFleet, TouchingAPersonEndsTheRunAsAPersonCollision) {
  const Scenario s = load_scenario_text(
      corridor_yaml("people: [{name: ann, start: [2.6, 0.35], waypoints: [[2.6, 0.35]], "
                    "cyclic: false}]\n"),
      "corridor.yaml");
  ASSERT_TRUE(s.is_fleet());
  const FleetResult f = simulate_fleet(s);
  ASSERT_EQ(f.collisions.size(), 1u);
  EXPECT_EQ(f.collisions[0].kind, ContactKind::Person);
  EXPECT_EQ(f.collisions[0].other, 0);
  EXPECT_EQ(f.robots[0].status, RunStatus::Collision);
  EXPECT_EQ(f.crowd.metrics.person_contacts, 1);
  EXPECT_LE(f.crowd.metrics.min_person_gap, 0.0);
  const auto j = fleet_summary_to_json(f);
  EXPECT_EQ(j["fleet"]["person_collisions"], 1);
  EXPECT_EQ(j["fleet"]["robot_collisions"], 0);
  EXPECT_EQ(j["collisions"][0]["kind"], "person");
  EXPECT_EQ(j["collisions"][0]["other"], "ann");
  EXPECT_EQ(j["crowd"]["people"], 1);
}

// A forklift that never stops (stop_distance 0) drives into a robot: kind forklift.
TEST(CrowdFleet, AForkliftThatDoesNotStopHitsTheRobot) {
  const Scenario s = load_scenario_text(
      "world: {bounds: [0, 0, 8, 3]}\n"
      "robots: [{name: bot, start: [6, 1.5, 1.5707963], goal: [6, 2.5]}]\n"
      "controller: {v0: 0.01}\n"
      "forklifts: [{name: fk, route: [[1.5, 1.5], [7, 1.5]], stop_distance: 0, cyclic: false}]\n",
      "forklift.yaml");
  const FleetResult f = simulate_fleet(s);
  ASSERT_EQ(f.collisions.size(), 1u);
  EXPECT_EQ(f.collisions[0].kind, ContactKind::Forklift);
  EXPECT_EQ(f.crowd.metrics.forklift_contacts, 1);
  EXPECT_EQ(fleet_summary_to_json(f)["fleet"]["forklift_collisions"], 1);
  // With its scanner (the default 1 m) it stops short instead.
  const Scenario safe = load_scenario_text(
      "world: {bounds: [0, 0, 8, 3]}\n"
      "robots: [{name: bot, start: [6, 1.5, 1.5707963], goal: [6, 2.5]}]\n"
      "controller: {v0: 0.01}\n"
      "forklifts: [{name: fk, route: [[1.5, 1.5], [7, 1.5]], cyclic: false}]\n",
      "forklift.yaml");
  const FleetResult g = simulate_fleet(safe);
  EXPECT_TRUE(g.collisions.empty());
  EXPECT_GT(g.crowd.metrics.forklift_stopped_time, 0.0);
}

// The robots' sensors see a person as a disc: a controller that records the nearest sensed
// point finds it on the person's body, 0.4 m ahead (a 16-beam ring on the QuickBot).
TEST(CrowdFleet, RobotsSensePeopleAsDiscs) {
  Scenario s = load_scenario_text(
      "world: {bounds: [0, 0, 4, 3]}\n"
      "robot: {preset: quickbot, sensors: {lidar: {beams: 16, fov: 6.283185307, min_range: 0.02, "
      "max_range: 0.6}}}\n"
      "robots: [{name: bot, start: [1, 1.5, 0], goal: [3.5, 1.5]}]\n"
      "people: [{name: ann, start: [1.65, 1.5], waypoints: [[1.65, 1.5]], cyclic: false}]\n",
      "sense.yaml");
  double nearest = 1e9;
  s.set_controller("probe", make_controller([&](const Observation& obs) {
                     for (const Vec2& q : obs.sensed)
                       nearest = std::min(nearest, (q - obs.pose.position).norm());
                     return Command::velocity(Vec2::Zero());
                   }));
  FleetSimulation sim = make_fleet_simulation(s);
  sim.step();
  EXPECT_NEAR(nearest, 0.65 - 0.25, 1e-9);
}

// The crowd moves serially from the state at the start of each step: one thread or two, the same
// bits for the robots and for every person and forklift.
TEST(CrowdFleet, AnyNumberOfThreadsGivesTheSameResult) {
  std::string yaml =
      "world: {bounds: [0, 0, 10, 10]}\n"
      "robot: {preset: turtlebot3_burger}\n"
      "controller: {robot_avoidance: orca}\n"
      "sim: {t_max: 15}\n"
      "people:\n"
      "  - {start: [5, 1], waypoints: [[5, 9], [1, 5]]}\n"
      "  - {start: [1, 1], waypoints: [[9, 9]], speed: 0.8}\n"
      "  - {start: [9, 5], waypoints: [[1, 5]], radius: 0.3}\n"
      "forklifts: [{route: [[2, 7.5], [8, 7.5], [8, 8.5], [2, 8.5]], speed: 1.2, size: [1.6, "
      "0.8]}]\n"
      "robots:\n";
  for (int i = 0; i < 12; ++i) {
    const double x = 0.6 + 0.7 * i;
    yaml += "  - {start: [" + std::to_string(x) + ", 0.5, 1.57], goal: [" +
            std::to_string(9.4 - 0.7 * i) + ", 6.5]}\n";
  }
  const Scenario s = load_scenario_text(yaml, "crowd_threads.yaml");
  FleetSimulation one = make_fleet_simulation(s), two = make_fleet_simulation(s);
  ASSERT_EQ(two.threads_for(2), 2u);
  one.run(1);
  two.run(2);
  const FleetResult a = one.result(), b = two.result();
  EXPECT_EQ(fleet_summary_to_json(a).dump(), fleet_summary_to_json(b).dump());
  ASSERT_EQ(a.crowd.people.size(), 3u);
  for (std::size_t k = 0; k < a.crowd.people.size(); ++k) {
    ASSERT_EQ(a.crowd.people[k].samples.size(), b.crowd.people[k].samples.size());
    EXPECT_EQ(a.crowd.people[k].samples.back().x, b.crowd.people[k].samples.back().x);
    EXPECT_EQ(a.crowd.people[k].samples.back().y, b.crowd.people[k].samples.back().y);
  }
  EXPECT_EQ(a.crowd.forklifts[0].samples.back().x, b.crowd.forklifts[0].samples.back().x);
  EXPECT_GT(a.crowd.people[0].path_length, 5.0);  // they did walk
}

// A robot's wait_time counts the steps its body moved slower than 1 cm/s: one facing its goal
// drives off at once (0 s); one facing away turns on the spot first (V = v0 cos e stays under
// 1 cm/s until the heading error is below 86 degrees: a fraction of a second at the QuickBot's
// turn rate), then drives.
TEST(RobotWaitTime, CountsTheTimeTheBodyStandsStill) {
  const std::string yaml =
      "world: {bounds: [-1, -1, 3, 1]}\nrobot: {start: [0, 0, THETA]}\n"
      "goal: [2, 0]\n";
  auto run = [&](const std::string& theta) {
    std::string y = yaml;
    y.replace(y.find("THETA"), 5, theta);
    return simulate(load_scenario_text(y, "wait.yaml"));
  };
  const RunResult ahead = run("0");
  EXPECT_EQ(ahead.status, RunStatus::Reached);
  EXPECT_EQ(ahead.wait_time, 0.0);
  const RunResult behind = run("3.14159");
  EXPECT_EQ(behind.status, RunStatus::Reached);
  EXPECT_GT(behind.wait_time, 0.05);
  EXPECT_LT(behind.wait_time, 0.6);
}

// HuNavSim's factory agents: four people, init_pose and named goals in order, max_vel as speed.
TEST(CrowdFile, LoadsHuNavSimAgents) {
  const Scenario s = load_scenario_text(
      "world: {bounds: [-10, -12, 10, 4]}\n"
      "robot: {start: [-9, 3, 0]}\n"
      "goal: [-8, 3]\n"
      "people_file: " +
          std::string(FLOORNAV_TEST_DATA_DIR) + "/hunav/agents_factory.yaml\n",
      "hunav.yaml");
  ASSERT_EQ(s.crowd.people.size(), 4u);
  const PersonSpec& a = s.crowd.people[0];
  EXPECT_EQ(a.name, "agent1");
  EXPECT_EQ(a.start, Vec2(1.5, 0.0));
  ASSERT_EQ(a.waypoints.size(), 3u);
  EXPECT_EQ(a.waypoints[0], Vec2(4.98, -0.64));
  EXPECT_EQ(a.waypoints[2], Vec2(5.78, -8.25));
  EXPECT_EQ(a.speed, 1.5);
  EXPECT_EQ(a.radius, 0.5);
  EXPECT_EQ(a.goal_radius, 0.3);
  EXPECT_TRUE(a.cyclic);
  EXPECT_EQ(s.crowd.people[3].start, Vec2(-6.0, -1.68));
  EXPECT_TRUE(s.is_fleet());  // a lone robot among people runs as a fleet of one
}

// The target: a factory floor with ten people and two forklifts, at least 95 % of the deliveries
// and no contact with a person (nor a forklift, nor another robot).
TEST(CrowdFleet, FactoryFloorWithPeopleAndForklifts) {
  const Scenario s =
      load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/crowd/factory_people.yaml");
  ASSERT_EQ(s.crowd.people.size(), 10u);
  ASSERT_EQ(s.crowd.forklifts.size(), 2u);
  const FleetResult f = simulate_fleet(s);
  EXPECT_GE(100 * f.deliveries, 95 * f.delivery_count);
  EXPECT_EQ(f.crowd.metrics.person_contacts, 0);
  EXPECT_EQ(f.crowd.metrics.forklift_contacts, 0);
  EXPECT_TRUE(f.collisions.empty());
  EXPECT_GT(f.crowd.metrics.min_person_gap, 0.0);
  // The people did meet the robots, and the forklifts did wait for someone.
  EXPECT_GT(f.crowd.metrics.intrusions, 0);
  EXPECT_GT(f.crowd.metrics.forklift_stopped_time, 0.0);
}

// A lone robot's simulation has no crowd: asking for one with people is an error, not a run
// without them.
TEST(CrowdFleet, ALoneSimulationRefusesPeople) {
  const Scenario s = load_scenario_text(
      "world: {bounds: [0, 0, 4, 3]}\nrobot: {start: [1, 1, 0]}\ngoal: [3, 1]\n"
      "people: [{start: [2, 2.5], waypoints: [[3, 2.5]]}]\n",
      "lone.yaml");
  EXPECT_THROW(make_simulation(s), std::invalid_argument);
  EXPECT_EQ(simulate_fleet(s).robots.size(), 1u);
}

namespace {
/// FNV-1a over the bits of every recorded sample of every person.
std::uint64_t samples_hash(const CrowdResult& r) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&](double v) {
    std::uint64_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 8; ++i) h = (h ^ ((bits >> (8 * i)) & 0xffu)) * 1099511628211ull;
  };
  for (const CrowdTrack& t : r.people)
    for (const CrowdSample& s : t.samples) mix(s.x), mix(s.y), mix(s.theta);
  return h;
}
}  // namespace

// People push each other only within kPersonReach, so only the people of nearby cells are
// visited (10,000 people once cost 10^8 pair tests a step). The sums run in the same order as
// the all-pairs loop: the tracks are the same bit for bit (the hash was taken with that loop).
TEST(Crowd, ThePeoplesGridGivesTheAllPairsTracksBitForBit) {
  const World w = room(30, 30);
  CrowdSpec spec;
  Rng rng(11);
  for (int i = 0; i < 300; ++i) {
    const Vec2 start(rng.uniform(1.0, 29.0), rng.uniform(1.0, 29.0));
    const Vec2 goal(rng.uniform(1.0, 29.0), rng.uniform(1.0, 29.0));
    std::string name(1, 'p');
    name += std::to_string(i);
    spec.people.push_back({name, start, {goal}, rng.uniform(0.8, 1.4), 0.25, 0.3, true});
  }
  NoRobots none;
  Crowd crowd(spec, w, 0, true);
  for (int k = 0; k < 300; ++k) crowd.step(0.02 * k, 0.02, none.bodies());
  EXPECT_EQ(samples_hash(crowd.result()), 0x8c7286a71575957cull)
      << std::hex << samples_hash(crowd.result());
}

// The work of a people step is bounded by who stands near whom: people spread along a line test
// only their neighbours (not the 9900 pairs of everyone), and people packed within 4 m of each
// other test every ordered pair once, n (n - 1), and never more.
TEST(Crowd, OnlyPeopleNearEachOtherAreTestedAsPairs) {
  const std::size_t n = 100;
  const World line = room(5.0 * n + 10.0, 10.0);
  CrowdSpec spread;
  for (std::size_t k = 0; k < n; ++k) {
    const double x = 5.0 + 5.0 * static_cast<double>(k);
    std::string name(1, 'p');  // (not "p" + ...: GCC 12's -Wrestrict false positive)
    name += std::to_string(k);
    spread.people.push_back({name, {x, 2.0}, {{x, 8.0}}, 1.0, 0.25, 0.3, true});
  }
  NoRobots none;
  Crowd walking(spread, line, 0, false);
  for (int k = 0; k < 50; ++k) {
    walking.step(0.02 * k, 0.02, none.bodies());
    EXPECT_GT(walking.person_pairs_tested(), 0u) << "neighbours 5 m apart share 3 x 3 cells";
    EXPECT_LE(walking.person_pairs_tested(), 2 * n) << "step " << k;
  }

  const World square = room(10.0, 10.0);
  CrowdSpec packed;  // 42 people of radius 0.1 m, 0.3 m apart: all within 4 m of each other
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 6; ++j) {
      const Vec2 at(4.0 + 0.3 * i, 4.0 + 0.3 * j);
      packed.people.push_back({"q", at, {Vec2(8.0 - at.x(), at.y())}, 1.0, 0.1, 0.3, true});
    }
  const std::size_t m = packed.people.size();
  Crowd crowd(packed, square, 0, false);
  for (int k = 0; k < 20; ++k) {
    crowd.step(0.02 * k, 0.02, none.bodies());
    EXPECT_EQ(crowd.person_pairs_tested(), m * (m - 1)) << "step " << k;
  }
}

// People may not start touching one another: the scenario is refused, naming both people.
TEST(CrowdFile, PeopleStartingOnEachOtherAreRefusedWithThePairNamed) {
  const std::string head =
      "world: {bounds: [0, 0, 8, 6]}\nrobot: {start: [0.5, 0.5, 0]}\ngoal: [7, 0.5]\npeople:\n"
      "  - {name: alice, start: [4, 4], waypoints: [[1, 4]]}\n";
  try {
    load_scenario_text(head + "  - {name: bob, start: [4.5, 4], waypoints: [[7, 4]]}\n", "p.yaml");
    ADD_FAILURE() << "bodies touching at the start were accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where, "people[1] ('bob').start");
    EXPECT_NE(std::string(e.what()).find("touches person 0 ('alice') at (4, 4)"), std::string::npos)
        << e.what();
  }
  // Just apart (0.01 m between the bodies): accepted.
  EXPECT_NO_THROW(load_scenario_text(
      head + "  - {name: bob, start: [4.51, 4], waypoints: [[7, 4]]}\n", "p.yaml"));
}
