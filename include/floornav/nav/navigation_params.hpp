#pragma once
/// @file
/// The chapter supervisor's parameters: speeds, the switching distances of Fig 5.11, the goal
/// radius, the heading PID. All distances are clearances measured from the robot body's surface,
/// so one set of defaults fits robots of different sizes up to their sensor range. The layers
/// around the supervisor have their own types: PlannerParams, DwaParams, RobotAvoidanceParams,
/// SafetyParams (ControllerConfig holds them all).

#include <span>

#include "floornav/core/enum_names.hpp"
#include "floornav/nav/pid.hpp"

namespace floornav {

/// The chapter's four automata (nav/navigation_automaton.hpp).
enum class ControllerKind {
  GoToGoal,    ///< GTG only (eqs. 5.16-5.19): hits whatever is in the way
  HardSwitch,  ///< GTG <-> AO on |x - x_o| vs d_o (Fig 5.7): can chatter (Fig 5.9)
  Blended,     ///< sigma_1 u_GTG + sigma_2 u_AO (eq. 5.21)
  Hybrid,      ///< the complete automaton of Fig 5.11: GTG, FB-cw, FB-ccw, AO, STOP
};

inline constexpr EnumName<ControllerKind> kControllerKindNames[]{
    {ControllerKind::GoToGoal, "go_to_goal"},
    {ControllerKind::HardSwitch, "hard_switch"},
    {ControllerKind::Blended, "blended"},
    {ControllerKind::Hybrid, "hybrid"}};
constexpr std::span<const EnumName<ControllerKind>> enum_names(ControllerKind) {
  return kControllerKindNames;
}

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

  bool operator==(const NavigationParams&) const = default;

  /// Lists every field once, with its key and doc (core/param_fields.hpp).
  template <class Fields>
  static void fields(Fields& f) {
    using P = NavigationParams;
    f("v0", &P::v0, "cruise speed, m/s (cap on |u|)");
    f("gtg_a", &P::gtg_a, "shape of the capped go-to-goal gain K = v0(1-exp(-a|e|^2))/|e|, 1/m^2");
    f("d_o", &P::d_o,
      "clearance at which an obstacle is met (GTG -> FB; hard_switch GTG <-> AO), m");
    f("d_fb", &P::d_fb, "clearance that follow-boundary keeps, m");
    f("k_fb", &P::k_fb, "follow-boundary distance-keeping gain, 1/m");
    f("d_unsafe", &P::d_unsafe, "clearance below which avoid-obstacle takes over, m");
    f("hysteresis", &P::hysteresis, "AO is left at d_unsafe + hysteresis, m");
    f("progress_margin", &P::progress_margin,
      "delta of the progress guard |x-x_g| < d_tau - delta, m");
    f("epsilon", &P::epsilon, "goal radius: any mode -> STOP, m");
    f("blend_near", &P::blend_near, "blended: sigma_2 = 1 at this clearance, m");
    f("blend_far", &P::blend_far, "blended: sigma_2 = 0 beyond this clearance, m");
    f("obstacle_memory", &P::obstacle_memory, "seconds a sensed obstacle point is remembered");
    f("obstacle_range", &P::obstacle_range,
      "sensed points farther than this clearance are ignored by the behaviours, m (0: all)");
    f("clear_shot_corridor", &P::clear_shot_corridor,
      "m; > 0: a clear shot is a free corridor of the body's width this long towards the goal "
      "(0: eq. 5.27)");
    f("footprint_clearance", &P::footprint_clearance,
      "robots with a footprint: clearance from the footprint polygon, not the body disc");
    f("slow_when_turning", &P::slow_when_turning, "scale V by max(0, cos(heading error))");
    f("chatter_switches", &P::chatter_switches,
      "switches within chatter_window that count as chatter");
    f("chatter_window", &P::chatter_window, "window of the chatter (Zeno) detector, s");
    f.section("pid", &P::heading_pid);
  }
};

}  // namespace floornav
