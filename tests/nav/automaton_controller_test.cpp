#include "floornav/nav/automaton_controller.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "floornav/io/scenario_file.hpp"
#include "floornav/nav/navigation_automaton.hpp"
#include "floornav/scenario/simulate.hpp"

using namespace floornav;

namespace {

// Cruise far from the goal, slow down near it (a fat guard: in at 1.0 m, out at 1.2 m), stop at
// it. The memory counts the slow-downs and remembers when the last one began.
struct SlowDowns {
  int count{0};
  double since{-1.0};
};
using Automaton = HybridAutomaton<Observation, SlowDowns, Command>;

Automaton make_cruise_automaton() {
  Automaton::Builder b;
  const int cruise = b.add_mode(
      "cruise", [](const Observation&, const SlowDowns&) { return Command::unicycle(0.2, 0.0); });
  const int slow = b.add_mode("slow", [](const Observation&, const SlowDowns& m) {
    return Command::unicycle(0.05, 0.5 * m.count);
  });
  const int stop = b.add_mode(
      "stop", [](const Observation&, const SlowDowns&) { return Command::goal_reached(); }, true);
  b.add_edge_from_every_mode(stop, "at_goal", [](const Observation& o, const SlowDowns&) {
    return o.goal_distance() < 0.1;
  });  // edges 0 (cruise) and 1 (slow)
  b.add_edge(
      cruise, slow, "near",
      [](const Observation& o, const SlowDowns&) { return o.goal_distance() < 1.0; },
      [](const Observation& o, SlowDowns& m) {
        ++m.count;
        m.since = o.t;
      });  // edge 2
  b.add_edge(slow, cruise, "far", [](const Observation& o, const SlowDowns&) {
    return o.goal_distance() >= 1.2;
  });  // edge 3
  b.set_initial(cruise);
  return b.build();
}

Observation at_distance(double d, double t) {
  Observation o;
  o.t = t;
  o.dt = 0.01;
  o.pose = Pose2{Vec2(0.0, 0.0), 0.0};
  o.goal = Vec2(d, 0.0);
  return o;
}

Scenario chapter(const std::string& file) {
  return load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + file);
}

}  // namespace

TEST(AutomatonController, NamesItsModesAndGuardsAfterTheAutomaton) {
  const AutomatonController<SlowDowns> c(
      std::make_shared<const Automaton>(make_cruise_automaton()));
  EXPECT_EQ(c.mode_names(), (std::vector<std::string>{"cruise", "slow", "stop"}));
  EXPECT_EQ(c.guard_names(), (std::vector<std::string>{"at_goal", "at_goal", "near", "far"}));
  EXPECT_EQ(c.mode(), 0);
}

TEST(AutomatonController, EachDecisionIsOneEngineStepThenTheFlow) {
  AutomatonController<SlowDowns> c(std::make_shared<const Automaton>(make_cruise_automaton()));

  Decision d = c.decide(at_distance(3.0, 0.0));  // far: no guard holds
  EXPECT_EQ(d.mode, 0);
  EXPECT_EQ(d.guard, -1);
  EXPECT_EQ(d.command.kind(), Command::Kind::Unicycle);
  EXPECT_EQ(d.command.unicycle_command().v, 0.2);

  d = c.decide(at_distance(0.8, 0.01));  // near: edge 2 fires, its reset writes the memory
  EXPECT_EQ(d.mode, 1);
  EXPECT_EQ(d.guard, 2);
  EXPECT_EQ(c.state().memory.count, 1);
  EXPECT_EQ(c.state().memory.since, 0.01);
  // The command is the new mode's flow, reading the memory the reset wrote: 0.5 * 1 rad/s.
  EXPECT_EQ(d.command.unicycle_command().v, 0.05);
  EXPECT_EQ(d.command.unicycle_command().omega, 0.5);

  d = c.decide(at_distance(1.1, 0.02));  // inside the hysteresis band: stays slow, no guard
  EXPECT_EQ(d.mode, 1);
  EXPECT_EQ(d.guard, -1);
  EXPECT_NEAR(c.state().time_in_mode, 0.01, 1e-15);  // the adapter passes obs.dt to the engine

  d = c.decide(at_distance(0.05, 0.03));  // at the goal: the slow mode's at_goal edge (1)
  EXPECT_EQ(d.mode, 2);
  EXPECT_EQ(d.guard, 1);
  EXPECT_EQ(d.command.kind(), Command::Kind::GoalReached);
}

TEST(AutomatonController, ResetRestoresTheInitialModeAndMemory) {
  AutomatonController<SlowDowns> c(std::make_shared<const Automaton>(make_cruise_automaton()),
                                   SlowDowns{10, -1.0});
  c.decide(at_distance(0.8, 0.0));
  ASSERT_EQ(c.mode(), 1);
  EXPECT_EQ(c.state().memory.count, 11);
  c.reset();
  EXPECT_EQ(c.mode(), 0);
  EXPECT_EQ(c.state().memory.count, 10);  // the given initial memory, not a default one
  EXPECT_EQ(c.state().switches, 0);
  EXPECT_EQ(c.decide(at_distance(3.0, 0.0)).command.unicycle_command().v, 0.2);
}

// The built-in hard_switch kind (Fig 5.7), rebuilt from public pieces on the adapter, drives the
// circle-obstacle scenario exactly as the built-in one: the same steps, switches, transition log
// (times, edges, guard names), chatter and final pose, bit for bit.
TEST(AutomatonController, ARebuiltHardSwitchRunsBitForBitLikeTheBuiltInKind) {
  struct None {};
  using A = HybridAutomaton<Observation, None, Command>;
  const auto input = [](const Observation& o) {
    return make_navigation_input(o.pose.position, o.goal, o.points, o.robot->body_radius,
                                 *o.params);
  };
  Scenario s = chapter("circle_obstacle.yaml");
  s.robot().controller.kind = "hard_switch";
  const RunResult builtin = simulate(s);
  ASSERT_GT(builtin.chatter_episodes, 0);  // the scenario exercises chatter detection

  const NavigationParams p = s.robot().controller.params;
  A::Builder b;
  const int gtg = b.add_mode("go_to_goal", [&](const Observation& o, const None&) {
    return Command::velocity(input(o).u_gtg);
  });
  const int ao = b.add_mode("avoid_obstacle", [&](const Observation& o, const None&) {
    return Command::velocity(input(o).u_ao);
  });
  const int stop = b.add_mode(
      "stop", [](const Observation&, const None&) { return Command::goal_reached(); }, true);
  b.add_edge_from_every_mode(stop, "at_goal", [&](const Observation& o, const None&) {
    return input(o).goal_distance < p.epsilon;
  });
  b.add_edge(gtg, ao, "obstacle_within_d_o",
             [&](const Observation& o, const None&) { return input(o).clearance < p.d_o; });
  b.add_edge(ao, gtg, "obstacle_beyond_d_o",
             [&](const Observation& o, const None&) { return input(o).clearance >= p.d_o; });
  b.set_initial(gtg);
  s.set_controller("my_hard_switch", make_automaton_controller(b.build()));
  const RunResult mine = simulate(s);

  EXPECT_EQ(mine.status, RunStatus::Reached);
  EXPECT_EQ(mine.steps, builtin.steps);
  EXPECT_EQ(mine.mode_switches, builtin.mode_switches);
  EXPECT_EQ(mine.chatter_episodes, builtin.chatter_episodes);
  EXPECT_EQ(mine.first_chatter_time, builtin.first_chatter_time);
  EXPECT_EQ(mine.final_x, builtin.final_x);
  EXPECT_EQ(mine.final_y, builtin.final_y);
  EXPECT_EQ(mine.mode_names, builtin.mode_names);
  EXPECT_EQ(mine.guard_names, builtin.guard_names);
  ASSERT_EQ(mine.transitions.size(), builtin.transitions.size());
  for (std::size_t i = 0; i < mine.transitions.size(); ++i) {
    EXPECT_EQ(mine.transitions[i].time, builtin.transitions[i].time) << i;
    EXPECT_EQ(mine.transitions[i].from, builtin.transitions[i].from) << i;
    EXPECT_EQ(mine.transitions[i].to, builtin.transitions[i].to) << i;
    EXPECT_EQ(mine.transitions[i].edge, builtin.transitions[i].edge) << i;
  }
}

// A route of two goals: STOP's goal_reached turns the robot to the next goal and the simulator
// resets the controller, so the memory starts afresh for each goal (one slow-down per goal).
TEST(AutomatonController, EachGoalOfARouteStartsFromTheInitialState) {
  Scenario s = chapter("circle_obstacle.yaml");
  s.robot().goals = {Vec2(0.0, -0.7), Vec2(2.0, -0.7)};  // below the pillar, no obstacle between
  std::vector<int> counts_at_stop;
  Automaton::Builder b;
  const int drive = b.add_mode("drive", [](const Observation& o, const SlowDowns&) {
    return Command::velocity(go_to_goal_velocity(o.pose.position, o.goal, 0.15, 40.0));
  });
  const int stop = b.add_mode(
      "stop", [](const Observation&, const SlowDowns&) { return Command::goal_reached(); }, true);
  b.add_edge(
      drive, drive, "halfway",
      [](const Observation& o, const SlowDowns& m) {
        return m.count == 0 && o.goal_distance() < 0.3;
      },
      [](const Observation&, SlowDowns& m) { ++m.count; });
  b.add_edge(
      drive, stop, "at_goal",
      [](const Observation& o, const SlowDowns&) { return o.goal_distance() < 0.05; },
      [&counts_at_stop](const Observation&, SlowDowns& m) { counts_at_stop.push_back(m.count); });
  s.set_controller("route", make_automaton_controller(b.build()));
  const RunResult r = simulate(s);
  EXPECT_EQ(r.status, RunStatus::Reached);
  EXPECT_EQ(r.goals_reached, 2);
  // Had the memory survived the first goal, "halfway" (which needs count 0) would not fire again.
  EXPECT_EQ(counts_at_stop, (std::vector<int>{1, 1}));
  int halfway = 0;
  for (const Transition& t : r.transitions) halfway += r.guard_names[t.edge] == "halfway";
  EXPECT_EQ(halfway, 2);
}

// Pitfalls: a NaN command is refused (std::domain_error), an exception thrown by a guard ends
// the run and reaches the caller; neither is turned into an outcome.
TEST(AutomatonController, NaNCommandsAndExceptionsReachTheCaller) {
  struct None {};
  using A = HybridAutomaton<Observation, None, Command>;
  const auto build = [](A::Guard guard, A::Flow flow) {
    A::Builder b;
    const int drive = b.add_mode("drive", std::move(flow));
    const int stop = b.add_mode(
        "stop", [](const Observation&, const None&) { return Command::goal_reached(); }, true);
    b.add_edge(drive, stop, "guard", std::move(guard));
    return b.build();
  };
  const auto never = [](const Observation&, const None&) { return false; };
  const auto straight = [](const Observation&, const None&) { return Command::unicycle(0.1, 0); };

  Scenario s = chapter("circle_obstacle.yaml");
  s.set_controller("nan",
                   make_automaton_controller(build(never, [](const Observation& o, const None&) {
                     return Command::unicycle(o.t > 0.5 ? std::nan("") : 0.1, 0.0);
                   })));
  EXPECT_THROW(simulate(s), std::domain_error);

  s.set_controller("throws", make_automaton_controller(build(
                                 [](const Observation& o, const None&) -> bool {
                                   if (o.t > 0.5) throw std::runtime_error("guard failed");
                                   return false;
                                 },
                                 straight)));
  try {
    simulate(s);
    FAIL() << "the guard's exception was swallowed";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "guard failed");
  }
}
