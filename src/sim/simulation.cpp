#include "floornav/sim/simulation.hpp"

#include <utility>

#include "floornav/nav/navigation_controller.hpp"

namespace floornav {

namespace {
AgentSetup agent_setup(const World& world, const RobotTask& task, const SimConfig& sim,
                       std::string name) {
  AgentSetup a;
  a.world = &world;
  a.task = &task;
  a.sim = &sim;
  a.controller = ControllerMaker().make(
      task.controller, {task.robot, task.controller.params, task.name, 0, &world, sim.seed});
  a.seed = sim.seed;
  a.name = name.empty() ? task.name : std::move(name);
  return a;
}
}  // namespace

Simulation::Simulation(const World& world, const RobotTask& task, const SimConfig& sim,
                       std::string name)
    : scratch_(task.robot.sensors.size()), agent_(agent_setup(world, task, sim, std::move(name))) {}

void Simulation::sense_once() {
  if (sensed_) return;
  agent_.sense(scratch_);
  sensed_ = true;
}

bool Simulation::step() {
  if (agent_.finished()) return false;
  sense_once();
  sensed_ = false;
  return agent_.act(scratch_);
}

bool Simulation::step(const Command& command) {
  if (agent_.finished()) return false;
  sense_once();
  sensed_ = false;
  return agent_.act(scratch_, &command);
}

Observation Simulation::observe() {
  sense_once();  // once the run has ended too: the final observation is of the final pose
  return agent_.observe(scratch_);
}

const RunResult& Simulation::run() {
  while (step()) {
  }
  return result();
}

}  // namespace floornav
