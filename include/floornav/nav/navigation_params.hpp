#pragma once
/// @file
/// The supervisor's parameters: speeds, the switching distances of Fig 5.11, the goal radius.
/// All distances are clearances measured from the robot body's surface, so one set of defaults
/// fits robots of different sizes up to their sensor range.

#include <optional>
#include <string_view>

#include "floornav/nav/dwa_params.hpp"
#include "floornav/nav/pid.hpp"
#include "floornav/nav/planner_params.hpp"
#include "floornav/nav/safety_params.hpp"

namespace floornav {

/// The four controller kinds of the command-line contract.
enum class ControllerKind {
  GoToGoal,    ///< GTG only (eqs. 5.16-5.19): hits whatever is in the way
  HardSwitch,  ///< GTG <-> AO on |x - x_o| vs d_o (Fig 5.7): can chatter (Fig 5.9)
  Blended,     ///< sigma_1 u_GTG + sigma_2 u_AO (eq. 5.21)
  Hybrid,      ///< the complete automaton of Fig 5.11: GTG, FB-cw, FB-ccw, AO, STOP
};

std::optional<ControllerKind> parse_controller_kind(std::string_view name);
std::string_view to_string(ControllerKind kind);

/// How a robot avoids the other robots of its fleet (nav/robot_avoidance.hpp).
enum class RobotAvoidance {
  None,  ///< the chapter: other robots are obstacles like any other
  Orca,  ///< a reciprocal-velocity layer between the controller's command and the wheels
};

std::optional<RobotAvoidance> parse_robot_avoidance(std::string_view name);
std::string_view to_string(RobotAvoidance avoidance);

struct NavigationParams {
  double v0{0.15};               ///< m/s cruise speed, the cap on |u|
  double gtg_a{40.0};            ///< 1/m^2 shape of the capped GTG gain (eq. 5.19 note)
  double d_o{0.12};              ///< m: an obstacle this close is "met" (GTG -> FB, Fig 5.11)
  double d_fb{0.08};             ///< m: clearance that follow-boundary holds
  double k_fb{10.0};             ///< 1/m: distance-keeping gain of follow-boundary
  double d_unsafe{0.03};         ///< m: closer than this, AO takes over (FB -> AO)
  double hysteresis{0.02};       ///< m: AO is left only at d_unsafe + hysteresis (fat guard)
  double progress_margin{0.02};  ///< m: delta in |x - x_g| < d_tau - delta (eq. 5.26)
  double epsilon{0.05};          ///< m: goal radius, any -> STOP
  double blend_near{0.03};       ///< m: blended, sigma_2 = 1 at this clearance
  double blend_far{0.15};        ///< m: blended, sigma_2 = 0 beyond this clearance
  double obstacle_memory{1.0};   ///< s: sensed points are remembered this long (sparse IR rings)
  double obstacle_range{0.0};    ///< m clearance: farther sensed points are ignored (0: use all)
  /// m: 0 (the chapter): "clear shot" is eq. 5.27, <u_AO, u_GTG> > 0. Positive (an extension for
  /// dense clutter): no sensed point in the corridor of half-width body radius + d_unsafe
  /// reaching this far towards the goal (or to the goal, if nearer).
  double clear_shot_corridor{0.0};
  /// An extension for robots with a footprint polygon (the Jackal): the guards' clearance is the
  /// distance from the sensed points to the footprint instead of to the body disc.
  bool footprint_clearance{false};
  bool slow_when_turning{true};  ///< V *= max(0, cos e): turn before driving (an extension)
  int chatter_switches{8};       ///< this many switches ...
  double chatter_window{2.0};    ///< ... within this many seconds is a chatter (Zeno) episode
  PidGains heading_pid{};        ///< eqs. 5.12-5.15
  /// The planning layer over the automaton (nav/planner_controller.hpp); `kind: none` (the
  /// default) is the chapter alone.
  PlannerParams planner{};
  DwaParams dwa{};  ///< the `dwa` controller kind (nav/dwa_controller.hpp)
  /// Robot-robot avoidance (robot_avoidance.hpp); read by name, not by serialize().
  RobotAvoidance robot_avoidance{RobotAvoidance::Orca};
  double avoidance_range{1.0};    ///< m between centres: robots told to this one (NearbyRobot)
  double avoidance_horizon{2.0};  ///< s: ORCA's time horizon tau for other robots
  double avoidance_margin{0.02};  ///< m added to the sum of two robots' radii
  /// The safety layer between the controller and the wheels (nav/safety_layer.hpp); it is the
  /// simulator's, under every controller, so user controllers get it too.
  SafetyParams safety{};

  bool operator==(const NavigationParams&) const = default;

  template <class Archive>
  void serialize(Archive& a) {
    a("v0", v0, "cruise speed, m/s (cap on |u|)");
    a("gtg_a", gtg_a, "shape of the capped go-to-goal gain K = v0(1-exp(-a|e|^2))/|e|, 1/m^2");
    a("d_o", d_o, "clearance at which an obstacle is met (GTG -> FB; hard_switch GTG <-> AO), m");
    a("d_fb", d_fb, "clearance that follow-boundary keeps, m");
    a("k_fb", k_fb, "follow-boundary distance-keeping gain, 1/m");
    a("d_unsafe", d_unsafe, "clearance below which avoid-obstacle takes over, m");
    a("hysteresis", hysteresis, "AO is left at d_unsafe + hysteresis, m");
    a("progress_margin", progress_margin, "delta of the progress guard |x-x_g| < d_tau - delta, m");
    a("epsilon", epsilon, "goal radius: any mode -> STOP, m");
    a("blend_near", blend_near, "blended: sigma_2 = 1 at this clearance, m");
    a("blend_far", blend_far, "blended: sigma_2 = 0 beyond this clearance, m");
    a("obstacle_memory", obstacle_memory, "seconds a sensed obstacle point is remembered");
    a("obstacle_range", obstacle_range,
      "sensed points farther than this clearance are ignored by the behaviours, m (0: all)");
    a("clear_shot_corridor", clear_shot_corridor,
      "m; > 0: a clear shot is a free corridor of the body's width this long towards the goal "
      "(0: eq. 5.27)");
    a("footprint_clearance", footprint_clearance,
      "robots with a footprint: clearance from the footprint polygon, not the body disc");
    a("slow_when_turning", slow_when_turning, "scale V by max(0, cos(heading error))");
    a("chatter_switches", chatter_switches, "switches within chatter_window that count as chatter");
    a("chatter_window", chatter_window, "window of the chatter (Zeno) detector, s");
    a("avoidance_range", avoidance_range,
      "robot_avoidance: other robots within this distance (centres) are avoided, m");
    a("avoidance_horizon", avoidance_horizon, "robot_avoidance orca: time horizon tau, s");
    a("avoidance_margin", avoidance_margin,
      "robot_avoidance orca: added to the sum of two robots' radii, m");
    a.section("pid", heading_pid);
    a.section("planner", planner);
    a.section("dwa", dwa);
    a.section("safety", safety);
  }
};

}  // namespace floornav
