#pragma once
/// @file
/// The dynamic window approach's parameters (`controller.dwa`, used by `controller.kind: dwa`):
/// D. Fox, W. Burgard, S. Thrun, "The dynamic window approach to collision avoidance", IEEE
/// Robotics & Automation Magazine 4(1), 1997. The window itself comes from the robot's
/// acceleration limits (RobotSpec::max_acceleration, max_angular_acceleration).

namespace floornav {

struct DwaParams {
  double horizon{2.0};        ///< s each candidate (v, omega) is rolled out for
  double sim_step{0.1};       ///< s between the poses checked along a roll-out
  int v_samples{9};           ///< forward speeds sampled across the window (>= 2)
  int omega_samples{21};      ///< turn rates sampled across the window (>= 2)
  double heading{1.0};        ///< alpha: weight of the heading term (facing the goal at the end)
  double clearance{0.4};      ///< beta: weight of the clearance term (nearest obstacle on the arc)
  double velocity{0.3};       ///< gamma: weight of the velocity term (forward speed)
  double max_clearance{1.0};  ///< m: clearances beyond this score as this (open space is open)
  double margin{0.02};        ///< m: an arc closer than this to an obstacle is not admissible
  double range{0.0};  ///< m around the robot that the obstacle map covers; 0: v0 x horizon + 1 m

  bool operator==(const DwaParams&) const = default;

  /// Lists every field once, with its key and doc (core/param_fields.hpp).
  template <class Fields>
  static void fields(Fields& f) {
    using P = DwaParams;
    f("horizon", &P::horizon, "roll-out time of each candidate, s");
    f("sim_step", &P::sim_step, "time between checked poses on a roll-out, s");
    f("v_samples", &P::v_samples, "forward speeds sampled in the window");
    f("omega_samples", &P::omega_samples, "turn rates sampled in the window");
    f("heading", &P::heading, "alpha: weight of facing the goal");
    f("clearance", &P::clearance, "beta: weight of the clearance along the arc");
    f("velocity", &P::velocity, "gamma: weight of forward speed");
    f("max_clearance", &P::max_clearance, "clearance that scores full marks, m");
    f("margin", &P::margin, "arcs closer than this to an obstacle are inadmissible, m");
    f("range", &P::range, "obstacle map radius round the robot, m (0: v0 x horizon + 1)");
  }
};

}  // namespace floornav
