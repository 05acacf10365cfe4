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

#include <vector>

#include "floornav/common/rng.hpp"
#include "floornav/control/navigation_automaton.hpp"
#include "floornav/control/pid.hpp"
#include "floornav/sensing/obstacle_memory.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sim/run_result.hpp"
#include "floornav/sim/scenario.hpp"

namespace floornav {

class Simulation {
 public:
  /// The scenario must outlive the simulation.
  explicit Simulation(const Scenario& scenario);

  /// Advances one step; returns false once the run has ended (then it does nothing).
  bool step();
  /// Steps until the run ends; returns the result.
  const RunResult& run();

  bool finished() const { return finished_; }
  const Pose2& pose() const { return pose_; }
  double time() const { return t_; }
  const RunResult& result() const { return result_; }
  const NavigationAutomaton& automaton() const { return automaton_; }

 private:
  void finish(RunStatus status);

  const Scenario& scenario_;
  NavigationAutomaton automaton_;
  NavigationAutomaton::State state_;
  PidState pid_{};
  Rng rng_;
  ObstacleMemory memory_{};
  Pose2 pose_{};
  double t_{0.0};
  std::size_t goal_index_{0};
  bool finished_{false};
  bool use_memory_{false};
  Vec2 stuck_anchor_{Vec2::Zero()};
  double stuck_anchor_time_{0.0};
  double stuck_radius_{0.0};
  /// m: a lower bound on the body's clearance at pose_ (exact right after it is computed).
  /// Disc bodies only; it lets a step skip the clearance query and the per-ray inside test.
  double clearance_bound_{0.0};
  bool disc_body_{true};  ///< no footprint polygon: the body is the disc
  std::vector<SensorBeam> beams_;
  std::vector<double> ranges_;
  std::vector<Vec2> sensed_;
  std::vector<Vec2> points_;
  RunResult result_{};
};

/// Runs `scenario` to the end.
RunResult simulate(const Scenario& scenario);

}  // namespace floornav
