// The resolved configuration (scenario_writer.hpp) round-trips: loading what it writes gives an
// equal scenario, field by field and bit for bit, for every scenario in the repository and for
// files that use every kind of key (lidar, mounts, cones, footprints, fleets with a shared robot,
// maps of each format, obstacles of each shape).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "floornav/io/scenario_file.hpp"
#include "floornav/io/scenario_writer.hpp"
#include "floornav/world/occupancy_grid.hpp"

using namespace floornav;
namespace fs = std::filesystem;

namespace {

void expect_same_grid(const OccupancyGrid* a, const OccupancyGrid* b) {
  ASSERT_EQ(a == nullptr, b == nullptr);
  if (!a) return;
  ASSERT_EQ(a->width(), b->width());
  ASSERT_EQ(a->height(), b->height());
  EXPECT_EQ(a->resolution(), b->resolution());
  EXPECT_EQ(a->origin().position, b->origin().position);
  EXPECT_EQ(a->origin().theta, b->origin().theta);
  std::size_t differ = 0;
  for (int y = 0; y < a->height(); ++y)
    for (int x = 0; x < a->width(); ++x) differ += a->occupied(x, y) != b->occupied(x, y);
  EXPECT_EQ(differ, 0u);
}

void expect_same_robot(const RobotTask& a, const RobotTask& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.start.position, b.start.position);
  EXPECT_EQ(a.start.theta, b.start.theta);
  EXPECT_EQ(a.goals, b.goals);
  EXPECT_EQ(a.controller.kind, b.controller.kind);
  EXPECT_TRUE(a.controller.params == b.controller.params);
  const RobotSpec &r = a.robot, &q = b.robot;
  EXPECT_EQ(r.preset, q.preset);
  EXPECT_EQ(r.drive.wheel_radius, q.drive.wheel_radius);
  EXPECT_EQ(r.drive.track_width, q.drive.track_width);
  EXPECT_EQ(r.drive.max_wheel_speed, q.drive.max_wheel_speed);
  EXPECT_EQ(r.drive.min_wheel_speed, q.drive.min_wheel_speed);
  EXPECT_EQ(r.body_radius, q.body_radius);
  EXPECT_EQ(r.footprint, q.footprint);
  EXPECT_EQ(r.sensor_noise, q.sensor_noise);
  ASSERT_EQ(r.sensors.size(), q.sensors.size());
  for (std::size_t i = 0; i < r.sensors.size(); ++i) {
    SCOPED_TRACE("sensor " + std::to_string(i));
    EXPECT_EQ(r.sensors[i].mount.position, q.sensors[i].mount.position);
    EXPECT_EQ(r.sensors[i].mount.theta, q.sensors[i].mount.theta);
    EXPECT_EQ(r.sensors[i].min_range, q.sensors[i].min_range);
    EXPECT_EQ(r.sensors[i].max_range, q.sensors[i].max_range);
    EXPECT_EQ(r.sensors[i].cone_angle, q.sensors[i].cone_angle);
    EXPECT_EQ(r.sensors[i].cone_rays, q.sensors[i].cone_rays);
  }
}

/// Every field of two scenarios, the world's shapes and cells included.
void expect_same_scenario(const Scenario& a, const Scenario& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.robots_listed, b.robots_listed);
  EXPECT_EQ(a.sim.dt, b.sim.dt);
  EXPECT_EQ(a.sim.t_max, b.sim.t_max);
  EXPECT_EQ(a.sim.seed, b.sim.seed);
  EXPECT_EQ(a.sim.stuck_window, b.sim.stuck_window);
  EXPECT_EQ(a.sim.stuck_radius, b.sim.stuck_radius);
  EXPECT_EQ(a.sim.record_trajectory, b.sim.record_trajectory);
  EXPECT_EQ(a.sim.park_finished, b.sim.park_finished);
  ASSERT_EQ(a.robots.size(), b.robots.size());
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    SCOPED_TRACE("robot " + std::to_string(i));
    expect_same_robot(a.robots[i], b.robots[i]);
  }
  // People and forklifts, every field.
  ASSERT_EQ(a.crowd.people.size(), b.crowd.people.size());
  for (std::size_t i = 0; i < a.crowd.people.size(); ++i) {
    const PersonSpec &p = a.crowd.people[i], &q = b.crowd.people[i];
    EXPECT_EQ(p.name, q.name);
    EXPECT_EQ(p.start, q.start);
    EXPECT_EQ(p.waypoints, q.waypoints);
    EXPECT_EQ(p.speed, q.speed);
    EXPECT_EQ(p.radius, q.radius);
    EXPECT_EQ(p.goal_radius, q.goal_radius);
    EXPECT_EQ(p.cyclic, q.cyclic);
  }
  ASSERT_EQ(a.crowd.forklifts.size(), b.crowd.forklifts.size());
  for (std::size_t i = 0; i < a.crowd.forklifts.size(); ++i) {
    const ForkliftSpec &f = a.crowd.forklifts[i], &g = b.crowd.forklifts[i];
    EXPECT_EQ(f.name, g.name);
    EXPECT_EQ(f.route, g.route);
    EXPECT_EQ(f.speed, g.speed);
    EXPECT_EQ(f.size, g.size);
    EXPECT_EQ(f.stop_distance, g.stop_distance);
    EXPECT_EQ(f.cyclic, g.cyclic);
  }
  const World &w = *a.world, &v = *b.world;
  ASSERT_EQ(w.bounds().has_value(), v.bounds().has_value());
  if (w.bounds()) {
    EXPECT_EQ(w.bounds()->min, v.bounds()->min);
    EXPECT_EQ(w.bounds()->max, v.bounds()->max);
  }
  ASSERT_EQ(w.circles().size(), v.circles().size());
  for (std::size_t i = 0; i < w.circles().size(); ++i) {
    EXPECT_EQ(w.circles()[i].center, v.circles()[i].center);
    EXPECT_EQ(w.circles()[i].radius, v.circles()[i].radius);
  }
  EXPECT_EQ(w.polygons(), v.polygons());
  expect_same_grid(w.grid(), v.grid());
}

/// Writes the scenario, loads the text back (as if from `origin`) and compares.
void expect_round_trip(const Scenario& s, const fs::path& origin = "config.yaml") {
  const std::string yaml = scenario_to_yaml(s);
  SCOPED_TRACE(yaml.substr(0, 2000));
  const Scenario back = load_scenario_text(yaml, origin);
  expect_same_scenario(s, back);
  // And the JSON form is the YAML form's content: writing the reloaded scenario gives the same.
  EXPECT_EQ(scenario_to_json(back), scenario_to_json(s));
}

}  // namespace

TEST(ScenarioWriter, EveryRepositoryScenarioRoundTrips) {
  int tested = 0;
  for (const auto& e : fs::recursive_directory_iterator(FLOORNAV_SCENARIO_DIR)) {
    if (e.path().extension() != ".yaml") continue;
    SCOPED_TRACE(e.path().string());
    // Every scenario loads: the maps they name are in the repository (data/maps).
    const Scenario s = load_scenario_file(e.path());
    expect_round_trip(s);
    ++tested;
  }
  EXPECT_GE(tested, 28);  // every file under scenarios/
}

TEST(ScenarioWriter, EveryKindOfKeyRoundTrips) {
  const std::string world = R"(
world:
  bounds: [-1, -1, 6, 4]
  obstacles:
    - circle: {center: [1.1, 0.3], radius: 0.1}
    - polygon: [[1.5, -0.5], [1.8, -0.5], [1.8, -0.2]]
    - rectangle: {center: [2.5, 0.6], size: [0.2, 0.3], angle: 0.3}
    - point: [0.5, -0.6]
sim: {dt: 0.013, t_max: 33.3, seed: 18446744073709551615, stuck_window: 4, stuck_radius: 0.02,
      record_trajectory: false, park_finished: false}
)";
  // A lidar off the centre, turned; sonar-like cones; a footprint removed; custom mounts.
  for (const std::string robot : {
           "robot: {preset: jackal, start: [0.3, 0.2, -3.1], sensors: {lidar: {beams: 37, fov: "
           "2.2, min_range: 0.05, max_range: 2.5, mount: [0.1, -0.02, 0.7]}, noise: 0.01}, "
           "footprint: []}\ngoal: [5, 3]\n",
           "robot: {preset: turtlebot3_burger, start: [0, 0, 1], sensors: {lidar: {beams: 360, "
           "fov: 6.283185307, min_range: 0.1, max_range: 3}}}\ngoals: [[5, 3], [4, 0.5]]\n",
           "robot: {preset: pioneer_p3dx, start: [0, 2.5, 0], radius: 0.3, min_wheel_speed: 0.5, "
           "sensors: {cone_angle: 0.4, cone_rays: 5, max_range: 3}}\ngoal: [5, 3]\n"
           "controller: {kind: blended, d_o: 0.7, pid: {kp: 3, ki: 0.1, kd: 0.05}}\n",
           "robot: {start: [0, 0, 0.5], footprint: [[-0.05, -0.05], [0.06, 0], [-0.05, 0.05]], "
           "sensors: {mounts: [[0.05, 0, 0], [0, 0.05, 1.5707963267948966], [0, -0.05, -2]], "
           "min_range: 0.01, max_range: 0.5}}\ngoal: [5, 3]\ncontroller: {kind: hard_switch}\n",
       }) {
    SCOPED_TRACE(robot);
    expect_round_trip(load_scenario_text(world + robot, "test.yaml"));
  }
}

TEST(ScenarioWriter, FleetsWithASharedRobotRoundTrip) {
  const Scenario s = load_scenario_text(R"(
name: fleet
world: {bounds: [-1, -1, 6, 4]}
robot: {preset: khepera3, radius: 0.05, sensors: {max_range: 0.15, noise: 0.01}}
controller: {kind: blended}
robots:
  - {name: a, start: [0, 0, 0], goals: [[4, 1], [5, 3]]}
  - {start: [1, 0, 0], goal: [4, 2], radius: 0.06, controller: {kind: hybrid, v0: 0.08}}
  - {start: [2, 0, 0], goal: [1, 3], preset: quickbot}
)",
                                        "fleet.yaml");
  expect_round_trip(s);
  const auto j = scenario_to_json(s);
  EXPECT_EQ(j["robots"][1]["name"], "robot1");
  EXPECT_EQ(j["robots"][1]["controller"]["kind"], "hybrid");
  EXPECT_EQ(j["robots"][0]["controller"]["kind"], "blended");
  EXPECT_FALSE(j.contains("robot"));
}

// Overrides are applied before the config is written: it holds the values the run used.
TEST(ScenarioWriter, HoldsTheOverriddenValues) {
  const Scenario s = load_scenario_file(
      fs::path(FLOORNAV_SCENARIO_DIR) / "rectangle.yaml",
      std::vector<std::string>{"controller.kind=blended", "sim.dt=0.02", "robot.radius=0.07"});
  const auto j = scenario_to_json(s);
  EXPECT_EQ(j["controller"]["kind"], "blended");
  EXPECT_EQ(j["sim"]["dt"], 0.02);
  EXPECT_EQ(j["robot"]["radius"], 0.07);
  EXPECT_EQ(j["robot"]["preset"], "quickbot");
  EXPECT_EQ(j["controller"]["d_o"], 0.12);  // the preset's value, written out
  expect_round_trip(s);
}

// A map is named by its absolute path with the options it needs; the obstacles of an SDF or
// course world stay the map's (not written again as the file's own).
TEST(ScenarioWriter, MapsAreNamedByTheirFile) {
  const fs::path dir = fs::temp_directory_path() / "floornav_writer_maps";
  fs::create_directories(dir);
  {
    std::ofstream(dir / "tiny.map")
        << "type octile\nheight 4\nwidth 5\nmap\n@@@@@\n@...@\n@.@.@\n@@@@@\n";
    std::ofstream(dir / "w.sdf")
        << "<sdf version='1.6'><world name='w'><model name='m'><static>1</static><link "
           "name='l'><collision name='c'><geometry><cylinder><radius>0.2</radius><length>1</"
           "length></cylinder></geometry></collision></link><pose>2 0 0 0 0 0</pose></model></"
           "world></sdf>";
  }
  const Scenario grid = load_scenario_text(
      "world: {map: tiny.map, cell_size: 0.5}\nrobot: {start: [0.75, 1.25, 0], radius: 0.05, "
      "sensors: {max_range: 0.2}}\ngoal: [1.75, 1.25]\nsim: {dt: 0.005}\n",
      dir / "s.yaml");
  const auto j = scenario_to_json(grid);
  EXPECT_EQ(j["world"]["map"], (dir / "tiny.map").string());
  EXPECT_EQ(j["world"]["cell_size"], 0.5);
  expect_round_trip(grid, "/elsewhere/config.yaml");  // an absolute path: from anywhere
  const Scenario sdf = load_scenario_text(
      "world: {map: w.sdf, obstacles: [{circle: {center: [0, 2], radius: 0.3}}]}\nrobot: {start: "
      "[0, 0, 0]}\ngoal: [3, 1]\n",
      dir / "t.yaml");
  const auto k = scenario_to_json(sdf);
  EXPECT_EQ(k["world"]["obstacles"].size(), 1u);  // the file's circle, not the SDF's cylinder
  expect_round_trip(sdf);
  fs::remove_all(dir);
}
