// Your own hybrid automaton on floornav's engine (automaton/hybrid_automaton.hpp): go to goal and
// avoid obstacle, switched on the clearance (Fig 5.7), with a guard of your own, driven through
// AutomatonController. It runs twice on the same scenario:
//   thin guard: leave avoid-obstacle as soon as the clearance is back at d_o. The switch fires
//               back and forth every few steps: chatter (Zeno, Fig 5.9), which the run detects;
//   fat guard:  leave avoid-obstacle only 3 cm farther out than where it was entered (hysteresis,
//               a "fat" guard, section 5.3.3): the reset remembers the entry clearance, the guard
//               reads it. Far fewer switches, no chatter.
// It prints the start of each run's transition log (time, modes, the guard that fired, where).
// Usage: 03_custom_guard SCENARIO.yaml   (e.g. scenarios/circle_obstacle.yaml)
#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>

#include <floornav/floornav.hpp>

namespace {

using floornav::Command;
using floornav::Observation;
using floornav::Vec2;

// The automaton's memory, written only by resets: the clearance (m) at which avoid-obstacle was
// last entered.
struct Memory {
  double entry_clearance{0.0};
};
using Automaton = floornav::HybridAutomaton<Observation, Memory, Command>;

// m, from the body's surface to the nearest sensed (or remembered) obstacle point.
double clearance(const Observation& o) {
  double c = std::numeric_limits<double>::infinity();
  for (const Vec2& q : o.points)
    c = std::min(c, (q - o.pose.position).norm() - o.robot->body_radius);
  return c;
}
Vec2 u_gtg(const Observation& o) {
  return floornav::go_to_goal_velocity(o.pose.position, o.goal, o.params->v0, o.params->gtg_a);
}
Vec2 u_ao(const Observation& o) {
  return floornav::avoid_obstacle_velocity(o.pose.position, o.points, o.params->v0);
}

Automaton make_automaton(bool fat_guard, double d_o) {
  Automaton::Builder b;
  const int gtg = b.add_mode("go_to_goal", [](const Observation& o, const Memory&) {
    return Command::velocity(u_gtg(o));
  });
  const int ao = b.add_mode("avoid_obstacle", [](const Observation& o, const Memory&) {
    return Command::velocity(u_ao(o));
  });
  const int stop = b.add_mode(
      "stop", [](const Observation&, const Memory&) { return Command::goal_reached(); }, true);
  // Edges are tried in the order they are added: at_goal first.
  b.add_edge_from_every_mode(stop, "at_goal", [](const Observation& o, const Memory&) {
    return o.goal_distance() < o.params->epsilon;
  });
  b.add_edge(
      gtg, ao, "obstacle_within_d_o",
      [d_o](const Observation& o, const Memory&) { return clearance(o) < d_o; },
      [](const Observation& o, Memory& m) { m.entry_clearance = clearance(o); });  // the reset
  if (fat_guard)
    b.add_edge(ao, gtg, "clear_by_3_cm", [](const Observation& o, const Memory& m) {
      return clearance(o) >= m.entry_clearance + 0.03;
    });
  else
    b.add_edge(ao, gtg, "obstacle_beyond_d_o",
               [d_o](const Observation& o, const Memory&) { return clearance(o) >= d_o; });
  b.set_initial(gtg);
  return b.build();
}

void run(floornav::Scenario scenario, bool fat_guard) {
  const double d_o = scenario.robot().controller.params.d_o;
  scenario.set_controller(fat_guard ? "fat_guard" : "thin_guard",
                          floornav::make_automaton_controller(make_automaton(fat_guard, d_o)));
  const floornav::RunResult r = floornav::simulate(scenario);
  std::printf("%s guard: %s in %.1f s, %d switches, chatter episodes: %d",
              fat_guard ? "fat" : "thin", std::string(floornav::to_string(r.status)).c_str(),
              r.sim_time, r.mode_switches, r.chatter_episodes);
  if (r.chatter_episodes > 0) std::printf(" (the first at t = %.2f s)", r.first_chatter_time);
  std::printf("\n");
  const std::size_t shown = std::min<std::size_t>(r.transitions.size(), 6);
  for (std::size_t i = 0; i < shown; ++i) {
    const floornav::Transition& t = r.transitions[i];
    std::printf("  t = %6.2f s  %s -> %s  (%s)  at (%.3f, %.3f)\n", t.time,
                r.mode_names[t.from].c_str(), r.mode_names[t.to].c_str(),
                r.guard_names[t.edge].c_str(), r.transition_x[i], r.transition_y[i]);
  }
  if (r.transitions.size() > shown) std::printf("  ... %zu more\n", r.transitions.size() - shown);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENARIO.yaml\n", argv[0]);
    return 2;
  }
  try {
    const floornav::Scenario scenario = floornav::load_scenario_file(argv[1]);
    run(scenario, false);
    run(scenario, true);
    return 0;
  } catch (const floornav::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
