#pragma once
/// @file
/// How a run is simulated: the step, the limits, the seed, what is recorded. The simulator's own
/// settings, so they live with it; a scenario (scenario/scenario.hpp) holds one.

#include <cstdint>

namespace floornav {

/// Extra columns recorded with each trajectory row (only when SimConfig::record_trajectory is on):
/// what the controller saw and asked for. An output choice, not part of a scenario: not in
/// serialize(), so a scenario file cannot set it (the command line's `--record` does).
struct RecordOptions {
  bool command{false};  ///< u_x, u_y (m/s, the velocity asked for), v_cmd (m/s), omega_cmd (rad/s)
  bool heading{false};  ///< theta_d (rad, atan2 of u), heading_error (rad, theta_d - theta wrapped)
  bool clearance{false};  ///< m, the body's clearance at the recorded pose
  bool goal{false};       ///< goal_index, goal_x, goal_y (m): the goal being driven to
  bool ranges{false};     ///< range_0 ... range_{n-1} (m): each sensor's reading the step used

  bool any() const { return command || heading || clearance || goal || ranges; }
};

/// How a run is simulated.
struct SimConfig {
  double dt{0.01};        ///< s, fixed control and integration step
  double t_max{120.0};    ///< s, then the run ends as `timeout`
  std::uint64_t seed{1};  ///< the run's random seed (sensor noise)
  /// s: a robot that stays within stuck_radius this long, and comes less than a tenth of it
  /// nearer its goal, is `stuck` (a robot crawling towards its goal is not)
  double stuck_window{10.0};
  double stuck_radius{0.0};  ///< m; 0 means the robot's body radius
  /// s: a robot held up among moving bodies (robots, people, forklifts) waits this long before
  /// its run ends `stuck` as a deadlock (it waits in traffic; stuck_window is for the rest)
  double deadlock_window{60.0};
  /// s: a robot that moves among moving bodies without coming nearer its goal (by stuck_radius)
  /// for this long ends `stuck` as a livelock (circling a parked forklift)
  double livelock_window{180.0};
  bool record_trajectory{true};  ///< keep every step (for CSV and SVG); off in big batches
  bool park_finished{true};      ///< fleets: a robot that is done stays, an obstacle to others
  /// Steps between two recordings of every sensor's range (RunResult::ranges, for the HTML
  /// replay); 0 (the default) records none and costs nothing.
  int record_ranges_every{0};
  /// Steps between two more recordings of the ranges, besides record_ranges_every's (0: none): a
  /// second consumer's interval (the bag's beside the replay's, runner/run_outputs.hpp). Not a
  /// scenario key.
  int record_ranges_also_every{0};
  RecordOptions record{};  ///< extra trajectory columns (not a scenario key; see above)
  /// Sum the heading errors of RunResult::path_irregularity each step (an atan2); off, it stays
  /// NaN. Not a scenario key: VecSimulation's copies, whose results a learner does not read.
  bool path_irregularity{true};

  /// Lists every field once, with its key and doc (core/param_fields.hpp).
  template <class Fields>
  static void fields(Fields& f) {
    using P = SimConfig;
    f("dt", &P::dt, "fixed time step, s");
    f("t_max", &P::t_max, "simulated time limit, s");
    f("seed", &P::seed, "random seed (sensor noise)");
    f("stuck_window", &P::stuck_window,
      "a robot that stays within stuck_radius this long, not a tenth of it nearer its goal, is "
      "stuck, s");
    f("stuck_radius", &P::stuck_radius, "m; 0 means the body radius");
    f("deadlock_window", &P::deadlock_window,
      "a robot held up among moving bodies this long is stuck (deadlock), s");
    f("livelock_window", &P::livelock_window,
      "a robot moving among moving bodies without nearing its goal this long is stuck "
      "(livelock), s");
    f("record_trajectory", &P::record_trajectory, "keep every step for the CSV and SVG outputs");
    f("park_finished", &P::park_finished,
      "fleets: a robot that has finished stays where it stopped, an obstacle to the others");
    f("record_ranges_every", &P::record_ranges_every,
      "record every sensor's range every this many steps (0: never), for the HTML replay");
  }
};

}  // namespace floornav
