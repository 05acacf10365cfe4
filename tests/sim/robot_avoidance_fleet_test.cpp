// Fleets with robot avoidance (controller.robot_avoidance: orca): the outcomes the layer is for
// (robots that meet round a pillar, head on, in a 20-robot warehouse), and what it must not change
// (a lone robot, the bits across thread counts).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "floornav/io/scenario_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/scenario/simulate.hpp"

using namespace floornav;

namespace {

Scenario scenario_file(const std::string& name, std::vector<std::string> sets = {}) {
  return load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + name, sets);
}

int robot_collisions(const FleetResult& f) {
  int n = 0;
  for (const FleetCollision& c : f.collisions) n += c.other >= 0;
  return n;
}

// Two robots facing each other along y = 0, 1 m apart.
std::string head_on_yaml(const std::string& kind, const std::string& avoidance,
                         const char* safety = "on") {
  return "world: {bounds: [-2, -1, 2, 1]}\n"
         "robots:\n"
         "  - {name: a, start: [-0.5, 0, 0], goal: [1.5, 0]}\n"
         "  - {name: b, start: [0.5, 0, 3.141592653589793], goal: [-1.5, 0]}\n"
         "controller: {kind: " +
         kind + ", robot_avoidance: " + avoidance + ", safety: " + safety + "}\n";
}

// y of the robot's trajectory where it crosses x = 0.
double y_at_middle(const RunResult& r) {
  for (std::size_t k = 1; k < r.trajectory.size(); ++k)
    if ((r.trajectory[k - 1].x < 0.0) != (r.trajectory[k].x < 0.0)) return r.trajectory[k].y;
  return 0.0;
}

}  // namespace

// The failure the layer is for: four QuickBots follow a pillar in opposite pairs and meet head on.
// The chapter's automaton alone: all four collide; with the layer: all four arrive, no contact.
TEST(RobotAvoidance, FourRobotsRoundAPillarCollideWithoutTheLayerAndArriveWithIt) {
  const FleetResult none = simulate_fleet(scenario_file(
      "fleet_pillar.yaml", {"controller.robot_avoidance=none", "controller.safety=off"}));
  EXPECT_EQ(none.collided, 4);
  EXPECT_GE(robot_collisions(none), 2);
  const FleetResult orca = simulate_fleet(scenario_file("fleet_pillar.yaml"));
  EXPECT_EQ(orca.status, RunStatus::Reached);
  EXPECT_EQ(orca.reached, 4);
  EXPECT_TRUE(orca.collisions.empty());
  EXPECT_GT(orca.min_clearance, 0.0);
}

// Go-to-goal ignores everything it senses; the layer alone keeps two of them apart, each passing
// on its own right (robot a, heading +x, below the line; robot b, heading -x, above it).
TEST(RobotAvoidance, GoToGoalRobotsHeadOnPassOnTheRight) {
  const FleetResult none =
      simulate_fleet(load_scenario_text(head_on_yaml("go_to_goal", "none", "off"), "head_on.yaml"));
  EXPECT_EQ(none.collided, 2);
  const FleetResult f =
      simulate_fleet(load_scenario_text(head_on_yaml("go_to_goal", "orca"), "head_on.yaml"));
  EXPECT_EQ(f.collided, 0);
  EXPECT_EQ(f.reached, 2);
  EXPECT_GT(f.min_clearance, 0.0);
  EXPECT_LT(y_at_middle(f.robots[0]), -0.05);
  EXPECT_GT(y_at_middle(f.robots[1]), 0.05);
}

// Twenty robots, 60 deliveries through aisles and docks: every delivery, no contact. The chapter's
// automaton without the layer (and without the planner, which routes round the parked robots)
// loses deliveries on the same floor (robots circling after meeting others).
TEST(RobotAvoidance, TwentyRobotWarehouseMakesEveryDelivery) {
  const FleetResult f = simulate_fleet(scenario_file("fleet_warehouse.yaml"));
  EXPECT_EQ(f.robots.size(), 20u);
  EXPECT_EQ(f.delivery_count, 60);
  EXPECT_EQ(f.deliveries, 60);
  EXPECT_EQ(f.status, RunStatus::Reached);
  EXPECT_TRUE(f.collisions.empty());
  const FleetResult none = simulate_fleet(scenario_file(
      "fleet_warehouse.yaml", {"controller.planner.kind=none", "controller.robot_avoidance=none"}));
  EXPECT_LT(none.deliveries, 60);
  const FleetResult layer_alone =
      simulate_fleet(scenario_file("fleet_warehouse.yaml", {"controller.planner.kind=none"}));
  EXPECT_EQ(layer_alone.deliveries, 60);
  EXPECT_TRUE(layer_alone.collisions.empty());
}

// The existing fleets keep every delivery and lose no clearance to contact with the layer on.
TEST(RobotAvoidance, CrossingAndAislesStillArriveWithTheLayer) {
  for (const char* file : {"fleet_crossing.yaml", "fleet_aisles.yaml"}) {
    const FleetResult f = simulate_fleet(scenario_file(file, {"controller.robot_avoidance=orca"}));
    EXPECT_EQ(f.status, RunStatus::Reached) << file;
    EXPECT_EQ(f.deliveries, f.delivery_count) << file;
    EXPECT_TRUE(f.collisions.empty()) << file;
  }
}

// Alone, a robot is told of no one: the layer does nothing, bit for bit.
TEST(RobotAvoidance, ALoneRobotRunsExactlyAsWithoutIt) {
  const RunResult plain = simulate(scenario_file("factory_delivery.yaml"));
  const RunResult layered =
      simulate(scenario_file("factory_delivery.yaml", {"controller.robot_avoidance=orca"}));
  ASSERT_EQ(plain.trajectory.size(), layered.trajectory.size());
  for (std::size_t k = 0; k < plain.trajectory.size(); ++k) {
    ASSERT_EQ(plain.trajectory[k].x, layered.trajectory[k].x) << k;
    ASSERT_EQ(plain.trajectory[k].y, layered.trajectory[k].y) << k;
  }
}

// Told velocities are those of the start of the step, whatever the threads: the same bits.
TEST(RobotAvoidance, AnyNumberOfThreadsGivesTheSameResult) {
  std::string yaml =
      "world: {bounds: [0, 0, 6, 6], obstacles: [{circle: {center: [3, 3], radius: 0.4}}]}\n"
      "robot: {preset: quickbot, sensors: {noise: 0.003, lidar: {beams: 180, fov: 6.283185307, "
      "min_range: 0.02, max_range: 0.4}}}\n"
      "controller: {robot_avoidance: orca}\n"
      "sim: {t_max: 20}\n"
      "robots:\n";
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      if ((i == 2 || i == 3) && (j == 2 || j == 3)) continue;
      const double x = 0.5 + 1.0 * i, y = 0.5 + 1.0 * j;
      yaml += "  - {start: [" + std::to_string(x) + ", " + std::to_string(y) + ", 0.5], goal: [" +
              std::to_string(6.0 - x) + ", " + std::to_string(6.0 - y) + "]}\n";
    }
  const Scenario s = load_scenario_text(yaml, "orca_threads.yaml");
  FleetSimulation one = make_fleet_simulation(s), two = make_fleet_simulation(s);
  ASSERT_EQ(two.threads_for(2), 2u);
  one.run(1);
  two.run(2);
  EXPECT_EQ(fleet_summary_to_json(one.result()).dump(), fleet_summary_to_json(two.result()).dump());
}
