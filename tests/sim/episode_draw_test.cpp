// Episodes that differ (EpisodeDraw): starts and goals drawn free, in their area, from the seed;
// a fleet's drawn starts keep clear of each other and of the crowd; an area without a free pose
// is a DrawError. And a fleet stepped from outside (keep_sensing, step(commands)) runs as run().
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "floornav/io/scenario_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/robot/body_clearance.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/episode_draw.hpp"
#include "floornav/sim/fleet_simulation.hpp"

using namespace floornav;

namespace {

Scenario scenario_file(const std::string& name, std::vector<std::string> sets = {}) {
  return load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + name, sets);
}

}  // namespace

TEST(EpisodeDraw, StartsAndGoalsAreFreeInsideTheBoundsAndFollowTheSeed) {
  const Scenario s = scenario_file("rectangle.yaml");
  EpisodeDraw draw;
  draw.start = draw.goal = true;
  const Box2 bounds = *s.world->bounds();
  std::vector<Pose2> starts;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    RobotTask task = s.robot();
    Rng rng(seed);
    draw_episode(draw, *s.world, task, {}, rng);
    const Pose2 p = task.start;
    EXPECT_TRUE(bounds.contains(p.position));
    EXPECT_GT(body_clearance(*s.world, task.robot, p), 0.0) << seed;
    ASSERT_EQ(task.goals.size(), 1u);
    EXPECT_GT(s.world->clearance(task.goals[0]), task.robot.body_radius) << seed;
    EXPECT_GE((task.goals[0] - p.position).norm(), task.controller.params.epsilon);
    starts.push_back(p);
  }
  // The same seed draws the same episode; another seed another one.
  RobotTask again = s.robot();
  Rng rng(7);
  draw_episode(draw, *s.world, again, {}, rng);
  EXPECT_EQ(again.start.position, starts[6].position);
  EXPECT_EQ(again.start.theta, starts[6].theta);
  EXPECT_NE(starts[6].position, starts[7].position);
}

TEST(EpisodeDraw, RegionsAndDistancesHoldAndAFullRegionIsADrawError) {
  const Scenario s = scenario_file("rectangle.yaml");
  EpisodeDraw draw;
  draw.start = draw.goal = true;
  draw.start_region = Box2{{-0.4, -1.0}, {0.5, 1.0}};
  draw.goal_region = Box2{{1.6, -1.0}, {2.9, 1.0}};
  draw.min_goal_distance = 1.5;
  draw.max_goal_distance = 3.0;
  for (std::uint64_t seed = 1; seed <= 50; ++seed) {
    RobotTask task = s.robot();
    Rng rng(seed);
    draw_episode(draw, *s.world, task, {}, rng);
    EXPECT_TRUE(draw.start_region->contains(task.start.position));
    EXPECT_TRUE(draw.goal_region->contains(task.goals[0]));
    const double d = (task.goals[0] - task.start.position).norm();
    EXPECT_GE(d, 1.5);
    EXPECT_LE(d, 3.0);
  }
  draw.start_region = Box2{{1.05, -0.4}, {1.35, 0.4}};  // inside the rectangle
  draw.max_tries = 100;
  RobotTask task = s.robot();
  const Pose2 before = task.start;
  Rng rng(1);
  try {
    draw_episode(draw, *s.world, task, {}, rng);
    FAIL() << "no DrawError";
  } catch (const DrawError& e) {
    EXPECT_NE(std::string(e.what()).find("no free start pose for"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("[1.05, -0.4, 1.35, 0.4]"), std::string::npos) << e.what();
  }
  EXPECT_EQ(task.start.position, before.position);  // nothing drawn, nothing changed
}

TEST(EpisodeDraw, AFleetsStartsKeepClearOfEachOtherAndOfTheCrowd) {
  const Scenario s = scenario_file("crowd/factory_people.yaml");
  EpisodeDraw draw;
  draw.start = draw.goal = true;
  std::vector<Circle> discs;
  std::vector<OrientedBox> boxes;
  crowd_starts(s.crowd, discs, boxes);
  ASSERT_EQ(discs.size(), 10u);
  ASSERT_EQ(boxes.size(), 2u);
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::vector<RobotTask> tasks = s.robots;
    Rng rng(seed);
    draw_fleet_episode(draw, *s.world, tasks, {discs, boxes}, rng);
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      const Vec2 p = tasks[i].start.position;
      const double r = tasks[i].robot.body_radius;
      for (std::size_t j = 0; j < i; ++j)
        EXPECT_GT((tasks[j].start.position - p).norm(), r + tasks[j].robot.body_radius);
      for (const Circle& c : discs) EXPECT_GT((c.center - p).norm(), c.radius + r);
      for (const OrientedBox& b : boxes) EXPECT_GT(signed_distance(b, p), r);
    }
  }
}

TEST(FleetStepping, KeptSensingAndCommandsFromOutsideRunAsRun) {
  // Among people and forklifts: stepped from outside with no command, robot for robot the run.
  const Scenario s = scenario_file("crowd/factory_people.yaml", {"sim.t_max=1.5"});
  FleetSimulation whole = make_fleet_simulation(s), outside = make_fleet_simulation(s);
  whole.run(1);
  outside.keep_sensing();
  const std::vector<std::optional<Command>> none(s.robots.size());
  long long steps = 0;
  while (outside.step(none)) ++steps;
  EXPECT_EQ(steps + 1, whole.steps());
  EXPECT_EQ(fleet_summary_to_json(outside.result()).dump(),
            fleet_summary_to_json(whole.result()).dump());
  // A command drives its robot only; the others' controllers go on deciding.
  FleetSimulation driven = make_fleet_simulation(s);
  std::vector<std::optional<Command>> commands(s.robots.size());
  commands[0] = Command::unicycle(0.0, 0.0);
  for (int k = 0; k < 50; ++k) driven.step(commands);
  EXPECT_EQ(driven.robot(0).pose().position, s.robots[0].start.position);
  EXPECT_NE(driven.robot(1).pose().position, s.robots[1].start.position);
  EXPECT_THROW(driven.step(std::vector<std::optional<Command>>(2)), std::invalid_argument);
}
