// Scenario files: what is accepted, and one clear error for what is not.
#include <gtest/gtest.h>

#include <string>

#include "floornav/io/scenario_file.hpp"

using namespace floornav;

namespace {
const char* kGood = R"(
name: tiny
world:
  bounds: [-1, -1, 3, 1]
  obstacles:
    - circle: {center: [1.0, 0.3], radius: 0.1}
    - polygon: [[1.5, -0.5], [1.8, -0.5], [1.8, -0.2]]
    - rectangle: {center: [2.5, 0.6], size: [0.2, 0.2], angle: 0.3}
    - point: [0.5, -0.6]
robot:
  preset: quickbot
  start: [0, 0, 0]
goal: [2.5, 0]
controller:
  kind: hybrid
  d_o: 0.15
  pid: {kp: 5}
sim: {dt: 0.01, t_max: 30, seed: 7}
)";

Scenario load(const std::string& text, std::vector<std::string> sets = {}) {
  return load_scenario_text(text, "test.yaml", sets);
}

// Expects an InputError whose message contains every fragment.
void expect_error(const std::string& text, std::vector<std::string> fragments,
                  std::vector<std::string> sets = {}) {
  try {
    load(text, sets);
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    for (const auto& f : fragments)
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos)
          << "'" << e.what() << "' lacks '" << f << "'";
  }
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  return s.replace(pos, from.size(), to);
}
}  // namespace

TEST(ScenarioFile, ReadsEveryKey) {
  const Scenario s = load(kGood);
  EXPECT_EQ(s.name, "tiny");
  EXPECT_EQ(s.world->circles().size(), 2u);  // the circle and the point post
  EXPECT_EQ(s.world->polygons().size(), 2u);
  EXPECT_EQ(s.robot().robot.preset, "quickbot");
  EXPECT_DOUBLE_EQ(s.robot().controller.params.d_o, 0.15);
  EXPECT_DOUBLE_EQ(s.robot().controller.params.heading_pid.kp, 5.0);
  EXPECT_EQ(s.sim.seed, 7u);
  EXPECT_EQ(s.robot().goals.size(), 1u);
}

TEST(ScenarioFile, SetOverridesAnyKey) {
  const Scenario s = load(kGood, {"controller.kind=blended", "sim.dt=0.02",
                                  "robot.start=[0,0.1,1.57]", "controller.pid.kd=0.5"});
  EXPECT_EQ(s.robot().controller.kind, "blended");
  EXPECT_DOUBLE_EQ(s.sim.dt, 0.02);
  EXPECT_DOUBLE_EQ(s.robot().start.theta, 1.57);
  EXPECT_DOUBLE_EQ(s.robot().controller.params.heading_pid.kd, 0.5);
}

TEST(ScenarioFile, PresetValuesCanBeOverridden) {
  const Scenario s =
      load(replace(kGood, "preset: quickbot",
                   "preset: khepera3\n  radius: 0.06\n  sensors: {max_range: 0.25, noise: 0.01}"));
  EXPECT_DOUBLE_EQ(s.robot().robot.body_radius, 0.06);
  EXPECT_EQ(s.robot().robot.sensors.size(), 9u);
  EXPECT_DOUBLE_EQ(s.robot().robot.sensors[3].max_range, 0.25);
  EXPECT_DOUBLE_EQ(s.robot().robot.sensor_noise, 0.01);
}

TEST(ScenarioFile, UnknownKeysAreErrorsWithASuggestion) {
  expect_error(replace(kGood, "d_o: 0.15", "d_0: 0.15"),
               {"test.yaml", "line 16", "controller.d_0", "unknown key", "controller.d_o"});
  expect_error(replace(kGood, "name: tiny", "nmae: tiny"), {"nmae", "unknown key"});
  expect_error(kGood, {"--set", "sim.dtt", "unknown key"}, {"sim.dtt=0.1"});
}

TEST(ScenarioFile, WrongValuesAreErrors) {
  expect_error(replace(kGood, "kind: hybrid", "kind: bug2"),
               {"line 15", "controller.kind", "unknown controller 'bug2'"});
  expect_error(replace(kGood, "preset: quickbot", "preset: r2d2"),
               {"robot.preset", "unknown preset"});
  expect_error(replace(kGood, "dt: 0.01", "dt: -0.01"), {"sim.dt", "positive"});
  expect_error(replace(kGood, "dt: 0.01", "dt: 0.5"), {"sim.dt", "too large"});
  expect_error(replace(kGood, "dt: 0.01", "dt: .nan"), {"sim.dt", "not a finite number"});
  expect_error(replace(kGood, "dt: 0.01", "dt: fast"), {"sim.dt", "expected a number"});
  expect_error(replace(kGood, "t_max: 30", "t_max: 1e400"), {"sim.t_max", "out of the range"});
  expect_error(replace(kGood, "seed: 7", "seed: -3"), {"sim.seed", "negative"});
  expect_error(replace(kGood, "start: [0, 0, 0]", "start: [0, 0]"),
               {"robot.start", "expected 3 numbers, got 2"});
  expect_error(replace(kGood, "radius: 0.1}", "radius: -0.1}"),
               {"world.obstacles[0].circle.radius", "positive"});
  expect_error(
      replace(kGood, "[[1.5, -0.5], [1.8, -0.5], [1.8, -0.2]]", "[[1.5, -0.5], [1.8, -0.5]]"),
      {"world.obstacles[1].polygon", "at least 3 points"});
  expect_error(replace(kGood, "[[1.5, -0.5], [1.8, -0.5], [1.8, -0.2]]",
                       "[[0, 0.5], [0.4, 0.9], [0.4, 0.5], [0, 0.9]]"),
               {"crosses itself"});
  expect_error(replace(kGood, "bounds: [-1, -1, 3, 1]", "bounds: [3, -1, -1, 1]"),
               {"world.bounds", "xmin < xmax"});
  expect_error(replace(kGood, "d_o: 0.15", "d_o: 0.05"), {"controller.d_o", "larger than d_fb"});
}

TEST(ScenarioFile, StartAndGoalMustBeFree) {
  expect_error(replace(kGood, "start: [0, 0, 0]", "start: [1.0, 0.3, 0]"),
               {"robot.start", "overlaps an obstacle"});
  expect_error(replace(kGood, "goal: [2.5, 0]", "goal: [5, 0]"), {"goal", "outside the world"});
}

TEST(ScenarioFile, StructuralErrors) {
  expect_error("", {"empty"});
  expect_error("[1, 2, 3]", {"mapping"});
  expect_error("world: {bounds: [0,0,1,1]}\ngoal: [0.5, 0.5]\n", {"robot", "missing"});
  expect_error(replace(kGood, "goal: [2.5, 0]", "goal: [2.5, 0]\ngoals: [[1, 1]]"),
               {"either goal or goals"});
  expect_error("a: [1, 2\nb: {", {"test.yaml", "not valid YAML"});
  expect_error(replace(kGood, "    - point: [0.5, -0.6]",
                       "    - point: [0.5, -0.6]\n      circle: {center: [0, 0], radius: 1}"),
               {"exactly one of"});
  expect_error(kGood, {"--set", "KEY=VALUE"}, {"controller.kind"});
}

TEST(ScenarioFile, MissingFile) {
  try {
    load_scenario_file("/nonexistent/floornav.yaml");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos);
  }
}
