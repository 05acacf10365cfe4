// The controller interface: user controllers drive runs, fleets and batches through the same
// pipeline and saturation as the built-in kinds; what the simulator refuses; the observation.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "floornav/geometry/angle.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/kinematics/unicycle.hpp"
#include "floornav/nav/navigation_controller.hpp"
#include "floornav/scenario/simulate.hpp"

using namespace floornav;

namespace {

Scenario chapter(const std::string& name, std::vector<std::string> sets = {}) {
  return load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + name, sets);
}

// A go-to-goal of the user's: steer at the goal with a P gain, stop within 5 cm.
Command user_go_to_goal(const Observation& obs) {
  if (obs.goal_distance() < 0.05) return Command::goal_reached();
  const Vec2 e = obs.goal - obs.pose.position;
  const double heading_error = std::remainder(std::atan2(e.y(), e.x()) - obs.pose.theta, 2 * kPi);
  return Command::unicycle(0.1, 3.0 * heading_error);
}

}  // namespace

TEST(ControllerInterface, AUserControllerDrivesTheRun) {
  Scenario s = chapter("point_obstacle.yaml");
  s.set_controller("user_gtg", make_controller(user_go_to_goal, "steer"));
  s.robot().goals = {Vec2(0.0, 0.8)};  // away from the obstacle: a plain drive
  const RunResult r = simulate(s);
  EXPECT_EQ(r.status, RunStatus::Reached);
  ASSERT_EQ(r.mode_names, std::vector<std::string>{"steer"});
  EXPECT_EQ(r.mode_switches, 0);
  EXPECT_GT(r.path_length, 0.7);
}

TEST(ControllerInterface, TheBuiltInKindGivesTheSameRunThroughAFactory) {
  // The hybrid kind made by a user's factory is bit for bit the built-in kind.
  const Scenario builtin = chapter("rectangle.yaml");
  Scenario wrapped = builtin;
  wrapped.set_controller("hybrid_again", [](const ControllerContext& c) {
    ControllerConfig config;
    config.params = c.params;
    return make_builtin_controller(config, c);
  });
  const RunResult a = simulate(builtin), b = simulate(wrapped);
  ASSERT_EQ(a.trajectory.size(), b.trajectory.size());
  for (std::size_t i = 0; i < a.trajectory.size(); ++i) {
    ASSERT_EQ(a.trajectory[i].x, b.trajectory[i].x) << i;
    ASSERT_EQ(a.trajectory[i].y, b.trajectory[i].y) << i;
    ASSERT_EQ(a.trajectory[i].mode, b.trajectory[i].mode) << i;
  }
  EXPECT_EQ(a.transitions.size(), b.transitions.size());
  EXPECT_EQ(a.guard_names, b.guard_names);
}

TEST(ControllerInterface, EveryCommandKindGoesThroughTheSaturation) {
  // The QuickBot's wheels turn at most 130 RPM: 0.0325 * 13.61 = 0.44 m/s straight ahead.
  Scenario s = chapter("point_obstacle.yaml");
  const double v_max = max_forward_speed(s.robot().robot.drive);
  for (const Command c : {Command::unicycle(5.0, 0.0), Command::wheels(100.0, 100.0)}) {
    s.set_controller("flat_out", make_controller([c](const Observation&) { return c; }));
    Simulation sim = make_simulation(s);
    sim.step();
    const TrajectorySample& row = sim.result().trajectory.back();
    EXPECT_NEAR(row.v, v_max, 1e-12);
    EXPECT_NEAR(row.w_left, s.robot().robot.drive.max_wheel_speed, 1e-12);
  }
  // A velocity u goes through the heading PID: u straight behind the robot turns it on the spot
  // (slow_when_turning: V *= max(0, cos e) = 0 for e = pi).
  s.set_controller("behind", make_controller([](const Observation&) {
                     return Command::velocity(Vec2(-0.1, 0.0));
                   }));
  Simulation sim = make_simulation(s);
  sim.step();
  EXPECT_NEAR(sim.result().trajectory.back().v, 0.0, 1e-12);
  EXPECT_GT(std::abs(sim.result().trajectory.back().omega), 0.1);
}

TEST(ControllerInterface, RefusesNonFiniteCommandsAndUnnamedModes) {
  Scenario s = chapter("point_obstacle.yaml");
  s.set_controller("nan", make_controller([](const Observation&) {
                     return Command::unicycle(std::nan(""), 0.0);
                   }));
  EXPECT_THROW(simulate(s), std::domain_error);

  struct WrongMode : Controller {
    Decision decide(const Observation&) override { return {Command::unicycle(0.1, 0), 3}; }
  };
  s.set_controller("wrong_mode", [](const ControllerContext&) -> std::unique_ptr<Controller> {
    return std::make_unique<WrongMode>();
  });
  EXPECT_THROW(simulate(s), std::out_of_range);
}

TEST(ControllerInterface, AUsersExceptionEndsTheRunAndReachesTheCaller) {
  Scenario s = chapter("point_obstacle.yaml");
  int calls = 0;
  s.set_controller("throws", make_controller([&calls](const Observation& obs) {
                     if (++calls == 5)
                       throw std::runtime_error("user bug at t = " + std::to_string(obs.t));
                     return Command::unicycle(0.1, 0.0);
                   }));
  EXPECT_THROW(simulate(s), std::runtime_error);
  EXPECT_EQ(calls, 5);
}

TEST(ControllerInterface, ModesAndGuardsReportedByTheUserAreLogged) {
  // Two modes, switching every 10 steps by a named guard: the log, mode_time and chatter follow.
  struct Toggle : Controller {
    Toggle() : Controller({"left", "right"}, {"tick"}) {}
    Decision decide(const Observation& obs) override {
      if (obs.goal_distance() < 0.05) return Command::goal_reached();
      const int step = static_cast<int>(std::lround(obs.t / obs.dt));
      int guard = -1;
      if (step > 0 && step % 10 == 0) {
        mode_ = 1 - mode_;
        guard = 0;
      }
      return {Command::unicycle(0.05, mode_ == 0 ? 0.5 : -0.5), mode_, guard};
    }
    int mode() const override { return mode_; }
    int mode_{0};
  };
  Scenario s = chapter("point_obstacle.yaml", {"sim.t_max=1.0"});
  s.set_controller("toggle", [](const ControllerContext&) -> std::unique_ptr<Controller> {
    return std::make_unique<Toggle>();
  });
  const RunResult r = simulate(s);
  EXPECT_EQ(r.status, RunStatus::Timeout);
  ASSERT_EQ(r.transitions.size(), 9u);  // at steps 10, 20, ..., 90 of 100
  EXPECT_EQ(r.transitions[0].from, 0);
  EXPECT_EQ(r.transitions[0].to, 1);
  EXPECT_EQ(r.transitions[0].edge, 0);
  EXPECT_NEAR(r.transitions[0].time, 0.11, 1e-12);  // decided in the step from t = 0.10
  EXPECT_EQ(r.guard_names, std::vector<std::string>{"tick"});
  EXPECT_NEAR(r.mode_time[0] + r.mode_time[1], 1.0, 1e-9);
  EXPECT_EQ(r.chatter_episodes, 1);  // 8 switches within 2 s: the default chatter rule
}

TEST(ControllerInterface, ObserveSensesOncePerStep) {
  // With sensor noise, observing before each step must not draw extra noise: the run is the
  // same as stepping alone, and the observation is what the controller saw.
  Scenario s = chapter("rectangle.yaml", {"robot.sensors.noise=0.01"});
  Simulation plain = make_simulation(s), observed = make_simulation(s);
  for (int i = 0; i < 300; ++i) {
    const Observation obs = observed.observe();
    ASSERT_EQ(obs.ranges.size(), 5u);
    ASSERT_EQ(obs.t, observed.time());
    plain.step();
    observed.step();
    ASSERT_EQ(plain.pose().position.x(), observed.pose().position.x()) << i;
    ASSERT_EQ(plain.pose().position.y(), observed.pose().position.y()) << i;
  }
}

TEST(ControllerInterface, AnExternalCommandDrivesThroughTheSameSaturation) {
  const Scenario s = chapter("point_obstacle.yaml");
  Simulation sim = make_simulation(s);
  sim.step(Command::unicycle(10.0, 0.0));
  const double v_max = max_forward_speed(s.robot().robot.drive);
  EXPECT_NEAR(sim.result().trajectory.back().v, v_max, 1e-12);
  EXPECT_NEAR(sim.pose().position.x(), s.robot().start.position.x() + v_max * s.sim.dt, 1e-12);
}

TEST(ControllerInterface, FleetsMakeOneControllerPerRobot) {
  Scenario s = chapter("fleet_crossing.yaml");
  std::vector<std::size_t> made;
  s.set_controller("per_robot", [&made](const ControllerContext& c) {
    made.push_back(c.robot_index);
    ControllerConfig config;
    config.params = c.params;
    return make_builtin_controller(config, c);
  });
  const FleetResult f = simulate_fleet(s);
  EXPECT_EQ(made.size(), s.robots.size());
  for (std::size_t i = 0; i < made.size(); ++i) EXPECT_EQ(made[i], i);
  EXPECT_EQ(f.reached, static_cast<int>(s.robots.size()));
}

TEST(ControllerInterface, AnExceptionOnAFleetThreadReachesTheCaller) {
  // 24 lidar robots: two threads' worth of rays, so robots step on a worker thread too.
  std::string yaml =
      "world: {bounds: [0, 0, 6, 6]}\n"
      "robot: {preset: turtlebot3_burger}\n"
      "sim: {t_max: 3}\n"
      "robots:\n";
  for (int i = 0; i < 24; ++i) {
    const double x = 0.6 + 1.2 * (i % 5), y = 0.6 + 1.2 * (i / 5);
    yaml += "  - {start: [" + std::to_string(x) + ", " + std::to_string(y) + ", 0], goal: [" +
            std::to_string(x) + ", " + std::to_string(y + 0.5) + "]}\n";
  }
  Scenario s = load_scenario_text(yaml, "lidars.yaml");
  s.set_controller("last_one_throws", [](const ControllerContext& c) {
    const bool bad = c.robot_index == 23;  // on the second thread's slice
    return make_controller([bad](const Observation& obs) -> Command {
      if (bad && obs.t > 0.5) throw std::runtime_error("robot 23 fails");
      return Command::unicycle(0.05, 0.0);
    })(c);
  });
  FleetSimulation fleet = make_fleet_simulation(s);
  ASSERT_EQ(fleet.threads_for(2), 2u);
  EXPECT_THROW(fleet.run(2), std::runtime_error);
}
