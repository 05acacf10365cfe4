#pragma once
/// @file
/// The fixed-step simulator. One step:
///   1. sense: cast the robot's range sensors, turn returns into world points (+ short memory);
///   2. supervise: evaluate the current mode's guards, take at most one transition and reset;
///   3. control: the mode's flow gives u; u -> theta_d -> omega (PID) -> (V, omega) (Fig 5.12);
///   4. saturate: (V, omega) -> wheel speeds within the motor limits, keeping omega;
///   5. integrate: the unicycle along its exact arc over dt;
///   6. check: clearance and collision (the body is a disc), goal, stuck, time limit;
///   7. record: metrics, and the trajectory row when recording.
/// A run ends `reached` (every goal), `collision`, `timeout` (t_max) or `stuck` (the robot stayed
/// within stuck_radius for stuck_window seconds). The step never throws and allocates nothing
/// once running (trajectory recording aside; the transition log is reserved for 1024 switches and
/// grows only beyond that; tests/allocation_test.cpp checks). Same scenario and seed: the same
/// trajectory, bit for bit.

#include "floornav/nav/navigation_automaton.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/robot_agent.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// One robot alone in its world: the scenario's robot, start, goals and controller. (A
/// scenario's `robots` fleet, if any, is FleetSimulation's.)
class Simulation {
 public:
  /// The scenario must outlive the simulation.
  explicit Simulation(const Scenario& scenario);

  /// Advances one step; returns false once the run has ended (then it does nothing).
  bool step() { return agent_.step(scratch_); }
  /// Steps until the run ends; returns the result.
  const RunResult& run();

  bool finished() const { return agent_.finished(); }
  const Pose2& pose() const { return agent_.pose(); }
  double time() const { return agent_.time(); }
  const RunResult& result() const { return agent_.result(); }
  const NavigationAutomaton& automaton() const { return automaton_; }

 private:
  NavigationAutomaton automaton_;
  SensingScratch scratch_;
  RobotAgent agent_;
};

/// Runs `scenario` to the end.
RunResult simulate(const Scenario& scenario);

}  // namespace floornav
