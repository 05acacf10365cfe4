// The scenes that `floornav bench` and the Google Benchmark binary time
// (floornav/scenario/factory_floor.hpp): what they time must be navigation, robots touring their
// goals without a contact, not robots pinned against a wall or ended by a crash.

#include <gtest/gtest.h>

#include <memory>

#include "floornav/scenario/factory_floor.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/world/world.hpp"

using namespace floornav;

namespace {

std::shared_ptr<const World> bench_floor() {
  static const auto floor = std::make_shared<const World>(make_factory_floor({}));
  return floor;
}

double mean_path(const FleetResult& r) {
  double driven = 0.0;
  for (const RunResult& robot : r.robots) driven += robot.path_length;
  return driven / static_cast<double>(r.robots.size());
}

// The 50-polygon floor's robot (index 0, the one the one-robot cases time) with `beams` lidar
// beams (0: the QuickBot's IR): its tour of four goals across the floor ends reached, without
// touching anything, as shipped.
void expect_tour_of_the_bench_floor(int beams) {
  Scenario s = make_factory_floor_scenario(bench_floor(), beams);
  s.sim.t_max = 900.0;
  const RunResult r = simulate(s);
  EXPECT_EQ(r.status, RunStatus::Reached) << "goals reached " << r.goals_reached;
  EXPECT_EQ(r.goals_reached, 4);
  EXPECT_FALSE(r.collided);
  EXPECT_GT(r.min_clearance, 0.0);
}

}  // namespace

TEST(BenchScenes, TheQuickBotToursTheBenchFloorWithoutAContact) {
  expect_tour_of_the_bench_floor(0);
}

TEST(BenchScenes, TheLidarRobotToursTheBenchFloorWithoutAContact) {
  expect_tour_of_the_bench_floor(180);
}

// The fleet cases time the first steps of their fleets: robots deliver and none touches a rack,
// a wall or another robot.
TEST(BenchScenes, TheWarehouseFleetDeliversWithoutAContact) {
  Scenario s =
      make_fleet_scenario(std::make_shared<const World>(make_fleet_warehouse(200)), 200, 0);
  s.sim.t_max = 120.0;
  const FleetResult r = simulate_fleet(s, 2);
  EXPECT_EQ(r.collided, 0);
  EXPECT_TRUE(r.collisions.empty());
  EXPECT_GT(r.min_clearance, 0.0);
  EXPECT_GT(r.deliveries, 0);
  // Robots drive: on average more than half the time at cruise speed.
  EXPECT_GT(mean_path(r), 0.5 * s.robot().controller.params.v0 * s.sim.t_max);
}

TEST(BenchScenes, TheLidarFleetOnTheBenchFloorDrivesWithoutAContact) {
  Scenario s = make_fleet_scenario(bench_floor(), 100, 180);
  s.sim.t_max = 10.0;
  const FleetResult r = simulate_fleet(s, 2);
  EXPECT_EQ(r.collided, 0);
  EXPECT_TRUE(r.collisions.empty());
  EXPECT_GT(r.min_clearance, 0.0);
  EXPECT_GT(mean_path(r), 0.5 * s.robot().controller.params.v0 * s.sim.t_max);
}
