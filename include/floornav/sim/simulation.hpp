#pragma once
/// @file
/// The fixed-step simulator. One step:
///   1. sense: cast the robot's range sensors, turn returns into world points (+ short memory);
///   2. decide: the robot's controller (nav/controller.hpp) gives a command; the built-in kinds
///      evaluate the current mode's guards, take at most one transition and reset, and give the
///      mode's flow u;
///   3. control: u -> theta_d -> omega (PID) -> (V, omega) (Fig 5.12); a unicycle or wheel
///      command goes straight to 4;
///   4. saturate: (V, omega) -> wheel speeds within the motor limits, keeping omega;
///   5. integrate: the unicycle along its exact arc over dt;
///   6. check: clearance and collision (the body is a disc), goal, stuck, time limit;
///   7. record: metrics, and the trajectory row when recording.
/// A run ends `reached` (every goal), `collision`, `timeout` (t_max) or `stuck` (the robot stayed
/// within stuck_radius, no nearer its goal, for stuck_window seconds). The step never throws and
/// allocates nothing once running (trajectory recording aside; the transition log is reserved for
/// 1024 switches and grows only beyond that; tests/allocation_test.cpp checks). Same scenario and
/// seed: the same trajectory, bit for bit.

#include <string>
#include <utility>

#include "floornav/sim/robot_agent.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/sim/run_result.hpp"
#include "floornav/sim/sim_config.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// One robot alone in its world. (Many robots in one world: FleetSimulation.)
class Simulation {
 public:
  /// World, task and sim must outlive the simulation; `name` names the run in its result.
  Simulation(const World& world, const RobotTask& task, const SimConfig& sim,
             std::string name = "");

  /// Advances one step; returns false once the run has ended (then it does nothing).
  bool step();
  /// Advances one step driven by `command` instead of the controller (see RobotAgent::act).
  bool step(const Command& command);
  /// What the controller sees now (senses once per step: a step() after it reuses the sensing).
  /// Once the run has ended: what the robot senses where it stopped (sensed once).
  Observation observe();
  /// Steps until the run ends; returns the result.
  const RunResult& run();

  bool finished() const { return agent_.finished(); }
  const Pose2& pose() const { return agent_.pose(); }
  double time() const { return agent_.time(); }
  const RunResult& result() const { return agent_.result(); }
  /// The result moved out, without a copy of its recorded rows (the simulation is then done).
  RunResult take_result() { return std::move(agent_.result()); }
  const RobotAgent& agent() const { return agent_; }

 private:
  void sense_once();
  SensingScratch scratch_;
  RobotAgent agent_;
  bool sensed_{false};  ///< scratch_ holds the sensing of the current step
};

}  // namespace floornav
