#include "floornav/sim/simulation.hpp"

namespace floornav {

namespace {
AgentSetup agent_setup(const Scenario& s, const NavigationAutomaton& automaton) {
  AgentSetup a;
  a.world = s.world.get();
  a.robot = &s.robot;
  a.start = s.start;
  a.goals = s.goals;
  a.automaton = &automaton;
  a.navigation = &s.navigation;
  a.sim = &s.sim;
  a.seed = s.sim.seed;
  a.name = s.name;
  return a;
}
}  // namespace

Simulation::Simulation(const Scenario& scenario)
    : automaton_(make_navigation_automaton(scenario.controller, scenario.navigation)),
      scratch_(scenario.robot.sensors.size()),
      agent_(agent_setup(scenario, automaton_)) {}

const RunResult& Simulation::run() {
  while (step()) {
  }
  return result();
}

RunResult simulate(const Scenario& scenario) {
  Simulation sim(scenario);
  sim.run();
  return sim.result();
}

}  // namespace floornav
