#include <gtest/gtest.h>

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/nav/navigation_automaton.hpp"

using namespace floornav;

namespace {
// A thermostat: the textbook two-mode automaton, with a counter as memory.
struct Temp {
  double value;
};
struct Count {
  int heats{0};
};
using Thermostat = HybridAutomaton<Temp, Count, double>;

Thermostat make_thermostat(double dwell = 0.0) {
  Thermostat::Builder b;
  const int off = b.add_mode("off", [](const Temp&, const Count&) { return -1.0; });
  const int on = b.add_mode("on", [](const Temp&, const Count&) { return +1.0; });
  const int stop = b.add_mode(
      "stop", [](const Temp&, const Count&) { return 0.0; }, true);
  b.add_edge_from_every_mode(stop, "too_hot",
                             [](const Temp& t, const Count&) { return t.value > 30; });
  b.add_edge(
      off, on, "cold", [](const Temp& t, const Count&) { return t.value < 18; },
      [](const Temp&, Count& c) { ++c.heats; }, dwell);
  b.add_edge(on, off, "warm", [](const Temp& t, const Count&) { return t.value > 22; });
  b.set_initial(off);
  b.set_chatter_rule(4, 1.0);
  return b.build();
}
}  // namespace

TEST(HybridAutomaton, GuardsResetsAndFlows) {
  const Thermostat a = make_thermostat();
  auto s = a.initial_state();
  EXPECT_EQ(a.modes()[s.mode].name, "off");
  EXPECT_EQ(a.flow({20}, s), -1.0);
  EXPECT_FALSE(a.step({20}, s, 0.1, 0.1));
  auto tr = a.step({17}, s, 0.2, 0.1);
  ASSERT_TRUE(tr);
  EXPECT_EQ(a.modes()[tr->to].name, "on");
  EXPECT_EQ(a.edges()[tr->edge].guard_name, "cold");
  EXPECT_EQ(s.memory.heats, 1);  // the reset wrote the memory
  EXPECT_EQ(a.flow({17}, s), 1.0);
  EXPECT_FALSE(a.step({17}, s, 0.3, 0.1));  // only the current mode's guards count
  ASSERT_TRUE(a.step({31}, s, 0.4, 0.1));   // priority: any -> stop
  EXPECT_TRUE(a.is_terminal(s));
}

TEST(HybridAutomaton, DwellDelaysAGuard) {
  const Thermostat a = make_thermostat(0.5);
  auto s = a.initial_state();
  for (int i = 1; i <= 4; ++i) EXPECT_FALSE(a.step({10}, s, 0.1 * i, 0.1));
  EXPECT_TRUE(a.step({10}, s, 0.5, 0.1));  // held 0.5 s
}

TEST(HybridAutomaton, ChatterIsDetected) {
  const Thermostat a = make_thermostat();
  auto s = a.initial_state();
  double t = 0;
  for (int i = 0; i < 10; ++i) {
    t += 0.05;
    a.step({(i % 2) ? 25.0 : 10.0}, s, t, 0.05);
  }
  EXPECT_EQ(s.switches, 10);
  EXPECT_EQ(s.chatter.episodes, 1);
  EXPECT_NEAR(s.chatter.first_time, 0.2, 1e-12);  // the 4th switch within 1 s
}

TEST(HybridAutomaton, BuilderRefusesBadStructures) {
  using A = HybridAutomaton<int, int, int>;
  auto flow = [](const int&, const int&) { return 0; };
  {
    A::Builder b;
    b.add_mode("a", flow);
    EXPECT_THROW(b.build(), std::logic_error);  // no terminal mode
  }
  {
    A::Builder b;
    b.add_mode("a", flow);
    b.add_mode("stop", flow, true);
    EXPECT_THROW(b.build(), std::logic_error);  // stop unreachable
  }
  {
    A::Builder b;
    const int x = b.add_mode("a", flow);
    const int stop = b.add_mode("stop", flow, true);
    b.add_edge(x, stop, "g", [](const int&, const int&) { return true; });
    b.add_edge(stop, x, "back", [](const int&, const int&) { return true; });
    EXPECT_THROW(b.build(), std::logic_error);  // leaves a terminal mode
  }
  {
    A::Builder b;
    const int x = b.add_mode("a", flow);
    b.add_mode("stop", flow, true);
    b.add_edge(x, 7, "g", [](const int&, const int&) { return true; });
    EXPECT_THROW(b.build(), std::logic_error);  // unknown mode
  }
}

// Fig 5.11 on hand-made inputs: the guards of the complete automaton.
TEST(NavigationAutomaton, Fig5_11Guards) {
  NavigationParams p;  // d_o 0.12, d_unsafe 0.03, progress margin 0.02, epsilon 0.05
  const NavigationAutomaton a = make_navigation_automaton(ControllerKind::Hybrid, p);
  auto s = a.initial_state();
  auto mode = [&] { return a.modes()[s.mode].name; };
  // Obstacle straight ahead (goal +x, wall at +x): u_AO = (-1, 0), u_GTG = (1, 0.1).
  NavigationInput in;
  in.x = Vec2(0, 0);
  in.goal = Vec2(2, 0.2);
  in.goal_distance = in.goal.norm();
  in.u_gtg = Vec2(1, 0.1);
  in.u_ao = Vec2(-1, 0);
  in.away = Vec2(-1, 0);
  in.obstacle_sensed = true;
  in.clearance = 0.2;  // beyond d_o: stay in GTG
  EXPECT_FALSE(a.step(in, s, 0.01, 0.01));
  in.clearance = 0.1;  // met at d_o; R(-pi/2)(-1,0) = (0,1): <u_GTG,(0,1)> = 0.1 > 0 -> clockwise
  ASSERT_TRUE(a.step(in, s, 0.02, 0.01));
  EXPECT_EQ(mode(), "follow_boundary_cw");
  EXPECT_DOUBLE_EQ(s.memory.d_tau, in.goal_distance);  // the reset of Fig 5.11
  // Clear shot but no progress yet: stay.
  in.u_ao = Vec2(0, 1);
  EXPECT_FALSE(a.step(in, s, 0.03, 0.01));
  // Progress (|x - x_g| < d_tau - delta) and clear shot (<u_AO, u_GTG> > 0): back to GTG.
  in.goal_distance = s.memory.d_tau - 0.05;
  ASSERT_TRUE(a.step(in, s, 0.04, 0.01));
  EXPECT_EQ(mode(), "go_to_goal");
  // Too close -> AO; back at d_unsafe + hysteresis with a clear shot -> GTG.
  in.clearance = 0.02;
  ASSERT_TRUE(a.step(in, s, 0.05, 0.01));
  EXPECT_EQ(mode(), "avoid_obstacle");
  in.clearance = 0.04;  // inside the hysteresis band: stay
  EXPECT_FALSE(a.step(in, s, 0.06, 0.01));
  in.clearance = 0.06;
  ASSERT_TRUE(a.step(in, s, 0.07, 0.01));
  EXPECT_EQ(mode(), "go_to_goal");
  in.goal_distance = 0.04;  // within epsilon
  ASSERT_TRUE(a.step(in, s, 0.08, 0.01));
  EXPECT_EQ(mode(), "stop");
}

TEST(NavigationAutomaton, ObstacleBesideThePathDoesNotTriggerFollowing) {
  const NavigationAutomaton a = make_navigation_automaton(ControllerKind::Hybrid, {});
  auto s = a.initial_state();
  NavigationInput in;
  in.goal_distance = 1.0;
  in.u_gtg = Vec2(1, 0);
  in.u_ao = Vec2(0.2, 1);  // wall below and slightly behind: a clear shot
  in.obstacle_sensed = true;
  in.clearance = 0.08;
  EXPECT_FALSE(a.step(in, s, 0.01, 0.01));
}

TEST(NavigationAutomaton, KindsHaveTheirModes) {
  auto names = [](ControllerKind k) {
    std::vector<std::string> out;
    const NavigationAutomaton a = make_navigation_automaton(k, {});
    for (const auto& m : a.modes()) out.push_back(m.name);
    return out;
  };
  EXPECT_EQ(names(ControllerKind::GoToGoal), (std::vector<std::string>{"go_to_goal", "stop"}));
  EXPECT_EQ(names(ControllerKind::HardSwitch),
            (std::vector<std::string>{"go_to_goal", "avoid_obstacle", "stop"}));
  EXPECT_EQ(names(ControllerKind::Blended), (std::vector<std::string>{"blended", "stop"}));
  EXPECT_EQ(names(ControllerKind::Hybrid).size(), 5u);
  EXPECT_EQ(parse_enum<ControllerKind>("hard_switch"), ControllerKind::HardSwitch);
  EXPECT_FALSE(parse_enum<ControllerKind>("bug2"));
  EXPECT_EQ(to_string(ControllerKind::GoToGoal), "go_to_goal");
}
