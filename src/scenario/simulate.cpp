#include "floornav/scenario/simulate.hpp"

#include <stdexcept>

namespace floornav {

void Scenario::set_controller(std::string kind, ControllerFactory factory) {
  for (RobotTask& t : robots) {
    t.controller.kind = kind;
    t.controller.factory = factory;
  }
}

Simulation make_simulation(const Scenario& scenario) {
  // A lone robot's simulation has no crowd: ignoring the people would be a silent wrong answer.
  if (!scenario.crowd.empty())
    throw std::invalid_argument("scenario '" + scenario.name +
                                "' has people or forklifts: only a fleet simulation "
                                "(make_fleet_simulation, simulate_fleet) moves them");
  return Simulation(*scenario.world, scenario.robot(), scenario.sim, scenario.name);
}

RunResult simulate(const Scenario& scenario) {
  Simulation sim = make_simulation(scenario);
  sim.run();
  return sim.take_result();
}

FleetSimulation make_fleet_simulation(const Scenario& scenario) {
  return FleetSimulation(*scenario.world, scenario.robots, scenario.sim, scenario.name,
                         &scenario.crowd);
}

FleetResult simulate_fleet(const Scenario& scenario, int threads) {
  FleetSimulation sim = make_fleet_simulation(scenario);
  sim.run(threads);
  return sim.take_result();
}

}  // namespace floornav
