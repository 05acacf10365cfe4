// The safety layer's promise attacked with floors nobody designed: generated shared floors
// (scenario/shared_floor.hpp) of 4 to 12 robots of mixed presets, controller kinds and speeds,
// people and forklifts on some, each from its own seed. Whatever a floor draws, no body ever
// touches another or the world. Progress is reported, and bounded from below only loosely: the
// mixed floors carry go-to-goal robots, which stop for what they meet and never get round it.
//
// FLOORNAV_SAFETY_FLOORS=N runs N floors instead of the suite's bounded count (CI's time).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "floornav/scenario/shared_floor.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/scenario/validate.hpp"
#include "support/property_count.hpp"

using namespace floornav;

namespace {

int floors_to_run(int default_count) {
  return test::property_count("FLOORNAV_SAFETY_FLOORS", default_count);
}

struct Tally {
  int floors{0}, robots{0}, delivered_all{0}, deliveries{0}, goals{0}, people{0}, forklifts{0};
  void add(const Scenario& s, const FleetResult& f) {
    ++floors;
    robots += static_cast<int>(f.robots.size());
    for (const RunResult& r : f.robots) delivered_all += r.reached_goal;
    deliveries += f.deliveries;
    goals += f.delivery_count;
    people += static_cast<int>(s.crowd.people.size());
    forklifts += static_cast<int>(s.crowd.forklifts.size());
  }
  void print(const char* what) const {
    std::printf(
        "%s: %d floors, %d robots (%d people, %d forklifts): %d robots delivered "
        "everything (%.1f %%), %d of %d deliveries\n",
        what, floors, robots, people, forklifts, delivered_all,
        robots ? 100.0 * delivered_all / robots : 0.0, deliveries, goals);
  }
};

// Every way a body can touch another: collisions of any kind, contacts with people and
// forklifts, and the clearance the runs measured.
void expect_no_contact(const Scenario& s, const FleetResult& f, std::uint64_t seed) {
  EXPECT_TRUE(f.collisions.empty()) << s.name << ": " << f.collisions.size() << " contacts, the "
                                    << "first of robot " << f.collisions.front().robot << " with "
                                    << to_string(f.collisions.front().kind) << " "
                                    << f.collisions.front().other << " (seed " << seed << ")";
  EXPECT_EQ(f.collided, 0) << s.name;
  EXPECT_EQ(f.crowd.metrics.person_contacts, 0) << s.name;
  EXPECT_EQ(f.crowd.metrics.forklift_contacts, 0) << s.name;
  EXPECT_GT(f.min_clearance, 0.0) << s.name;
}

}  // namespace

// The generator's floors are valid scenarios (a generator that drew invalid ones would test
// nothing), and differ from seed to seed.
TEST(SafetyProperty, GeneratedFloorsAreValidAndDiffer) {
  for (std::uint64_t seed = 1; seed <= 30; ++seed) {
    const Scenario s = make_shared_floor(seed);
    EXPECT_NO_THROW(validate_scenario(s, s.name)) << seed;
    EXPECT_GE(s.robots.size(), 2u) << seed;
  }
  EXPECT_NE(make_shared_floor(1).robots.front().start.position,
            make_shared_floor(2).robots.front().start.position);
  EXPECT_EQ(make_shared_floor(7).robots.back().goals, make_shared_floor(7).robots.back().goals);
}

// Mixed fleets: presets, controller kinds (the chapter's four, DWA, the planner stack) and
// speeds drawn per robot, people and forklifts on some floors: never a contact.
TEST(SafetyProperty, MixedFleetsOnGeneratedFloorsNeverTouch) {
  Tally tally;
  const int n = floors_to_run(16);
  for (int k = 0; k < n; ++k) {
    const std::uint64_t seed = 1000 + static_cast<std::uint64_t>(k);
    SharedFloorOptions o;
    o.t_max = 45.0;
    const Scenario s = make_shared_floor(seed, o);
    const FleetResult f = simulate_fleet(s, 1);
    expect_no_contact(s, f, seed);
    tally.add(s, f);
  }
  tally.print("mixed fleets");
  EXPECT_GT(tally.deliveries, tally.goals / 3) << "the fleets barely move";
}

// QuickBots with the shipped controller, as a factory runs them: never a contact, and nearly
// every robot delivers everything.
TEST(SafetyProperty, QuickBotFleetsOnGeneratedFloorsNeverTouchAndDeliver) {
  Tally tally;
  const int n = floors_to_run(40);
  for (int k = 0; k < n; ++k) {
    const std::uint64_t seed = 5000 + static_cast<std::uint64_t>(k);
    SharedFloorOptions o;
    o.mixed = false;
    const Scenario s = make_shared_floor(seed, o);
    const FleetResult f = simulate_fleet(s, 1);
    expect_no_contact(s, f, seed);
    tally.add(s, f);
  }
  tally.print("QuickBot fleets");
  EXPECT_GE(100 * tally.delivered_all, 80 * tally.robots);
}

// Mapless (controller.safety.map: sensed, as BARN runs): the lidar robots' layers (TurtleBot3's
// 360 degree lidar, the Jackal's 270 degree one) know only their own returns and those they
// remember near them. The mixed fleets again, people and forklifts on some floors: never a
// contact. (Five IR beams or a sonar ring leave gaps a corner fits in: mapless, those robots
// are safe only against what they happen to see, docs/SAFETY.md.)
TEST(SafetyProperty, MaplessLidarRobotsOnGeneratedFloorsNeverTouch) {
  Tally tally, known;
  int mapless = 0;
  const int n = floors_to_run(12);
  for (int k = 0; k < n; ++k) {
    const std::uint64_t seed = 9000 + static_cast<std::uint64_t>(k);
    SharedFloorOptions o;
    o.t_max = 45.0;
    Scenario s = make_shared_floor(seed, o);
    for (RobotTask& t : s.robots)
      if (t.robot.sensors.size() >= 270) {
        t.controller.safety.map = SafetyMap::Sensed;
        ++mapless;
      }
    const FleetResult f = simulate_fleet(s, 1);
    expect_no_contact(s, f, seed);
    tally.add(s, f);
    for (RobotTask& t : s.robots) t.controller.safety.map = SafetyMap::Known;
    known.add(s, simulate_fleet(s, 1));
  }
  tally.print("mixed fleets, lidar robots mapless");
  known.print("the same fleets on their maps");
  EXPECT_GT(mapless, n) << "the draw has too few lidar robots to test anything";
  // Knowing less, they may deliver a little less, but must not freeze.
  EXPECT_GE(4 * tally.deliveries, 3 * known.deliveries);
}
