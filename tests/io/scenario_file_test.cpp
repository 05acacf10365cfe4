// Scenario files: what is accepted, and one clear error for what is not.
#include <gtest/gtest.h>

#include <limits>
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

// The chapter's go-to-goal with nothing in the way: an empty, unbounded world is a scenario (its
// clearance is infinite, written as null), however the emptiness is written.
TEST(ScenarioFile, AnEmptyUnboundedWorldIsAScenario) {
  for (const char* world : {"world: {}", "world: {obstacles: []}"}) {
    SCOPED_TRACE(world);
    const Scenario s =
        load(std::string("name: open\n") + world + "\nrobot: {start: [0, 0, 0]}\ngoal: [4, 1]\n");
    EXPECT_FALSE(s.world->bounds().has_value());
    EXPECT_TRUE(s.world->circles().empty());
    EXPECT_TRUE(s.world->polygons().empty());
    EXPECT_EQ(s.world->clearance(Vec2(1.0, 0.5)), std::numeric_limits<double>::infinity());
  }
  // A world section is still required: leaving it out is more likely a mistake than a choice.
  expect_error("name: open\nrobot: {start: [0, 0, 0]}\ngoal: [4, 1]\n", {"world"});
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
    EXPECT_NE(std::string(e.what()).find("/nonexistent/floornav.yaml: does not exist"),
              std::string::npos)
        << e.what();
  }
}

// A message quoting megabytes of input stays one short line: its head and tail, with the number
// of bytes cut, and never a cut inside a UTF-8 character.
TEST(InputErrorMessage, LongMessagesAreCutToOneShortLine) {
  const std::string huge(5u << 20, 'x');
  const InputError e("f.yaml", "line 1", "expected a number, got '" + huge + "\xc3\xa9'");
  const std::string what = e.what();
  EXPECT_LT(what.size(), 600u);
  EXPECT_EQ(what.rfind("f.yaml:line 1: expected a number, got 'xxx", 0), 0u) << what;
  EXPECT_NE(what.find(" bytes cut ...] "), std::string::npos) << what;
  EXPECT_EQ(what.substr(what.size() - 3), "\xc3\xa9'");
  EXPECT_EQ(what.find('\n'), std::string::npos);
  // A command-line value has no file: the message starts with it.
  EXPECT_STREQ(InputError("", "--set sim.dt=-1", "must be positive").what(),
               "--set sim.dt=-1: must be positive");
}

// --set on a node that YAML aliases elsewhere changes that place only, not every alias.
TEST(ScenarioFile, SetOnAnAliasedNodeChangesOnlyThatPlace) {
  const std::string text = R"(
world: {bounds: [-1, -1, 5, 3]}
robots:
  - {start: [0, 0, 0], goals: &route [[4, 1], [4, 2]]}
  - {start: [1, 0, 0], goals: *route}
)";
  const Scenario s = load(text, {"robots[0].goals[0]=[3,1]"});
  EXPECT_EQ(s.robots[0].goals[0], Vec2(3, 1));
  EXPECT_EQ(s.robots[1].goals[0], Vec2(4, 1));
  EXPECT_EQ(s.robots[1].goals[1], Vec2(4, 2));
  const Scenario t = load(text, {"robots[1].goals=[[2,2]]"});
  EXPECT_EQ(t.robots[0].goals.size(), 2u);
  EXPECT_EQ(t.robots[1].goals.size(), 1u);
}

// A fleet's shared robot section is read as a layer under each entry: the entry's keys win,
// sensors merge key by key, and an unknown key in the shared section is named there.
TEST(ScenarioFile, FleetEntriesLayerOverTheSharedRobot) {
  const std::string text = R"(
world: {bounds: [-1, -1, 5, 3]}
robot: {preset: khepera3, radius: 0.05, sensors: {max_range: 0.15, noise: 0.01}}
robots:
  - {start: [0, 0, 0], goal: [4, 1]}
  - {start: [1, 0, 0], goal: [4, 2], radius: 0.06, sensors: {max_range: 0.18}}
)";
  const Scenario s = load(text);
  EXPECT_DOUBLE_EQ(s.robots[0].robot.body_radius, 0.05);
  EXPECT_DOUBLE_EQ(s.robots[1].robot.body_radius, 0.06);
  EXPECT_DOUBLE_EQ(s.robots[0].robot.sensors[0].max_range, 0.15);
  EXPECT_DOUBLE_EQ(s.robots[1].robot.sensors[0].max_range, 0.18);
  EXPECT_DOUBLE_EQ(s.robots[1].robot.sensor_noise, 0.01);  // merged from the shared sensors
  EXPECT_EQ(s.robots[1].robot.preset, "khepera3");
  expect_error(replace(text, "noise: 0.01", "nosie: 0.01"),
               {"line 3", "robot.sensors.nosie", "did you mean 'robot.sensors.noise'"});
}
