#pragma once
/// @file
/// The safety layer's parameters (`controller.safety`; nav/safety_layer.hpp). On by default for
/// every controller; `controller.safety: off` is the chapter's robot alone, for the teaching
/// scenes that must show a collision.

#include <span>

#include "floornav/core/enum_names.hpp"

namespace floornav {

/// What the safety layer knows of the static world.
enum class SafetyMap {
  Known,   ///< the floor plan (the simulator's world, as a robot's map) and this step's returns
  Sensed,  ///< its own range returns alone, remembered ones included (mapless benchmarks: BARN)
};

inline constexpr EnumName<SafetyMap> kSafetyMapNames[]{{SafetyMap::Known, "known"},
                                                       {SafetyMap::Sensed, "sensed"}};
constexpr std::span<const EnumName<SafetyMap>> enum_names(SafetyMap) {
  return kSafetyMapNames;
}

struct SafetyParams {
  bool enabled{true};
  SafetyMap map{SafetyMap::Known};
  /// m: the protective field beyond the body. A moving robot never enters it; a robot already
  /// inside (it started there, or something came to it) may only move so as not to come nearer.
  double margin{0.01};
  /// s: added to the time the robot needs to stop (a real base's latency); the stopping path is
  /// then driven at the command for one control period plus this, and braked at the robot's
  /// max_acceleration and max_angular_acceleration.
  double reaction_time{0.0};
  /// m: the slow-down field. Within this gap of anything, the forward speed is capped at
  /// slowdown_speed (0: no slow-down field; the protective field alone).
  double slowdown_distance{0.0};
  double slowdown_speed{0.3};  ///< m/s: the cap inside the slow-down field
  /// m: extra room kept from people (added to the margin for a person's body).
  double person_margin{0.0};

  bool operator==(const SafetyParams&) const = default;

  /// Lists every field once, with its key and doc (core/param_fields.hpp).
  template <class Fields>
  static void fields(Fields& f) {
    using P = SafetyParams;
    f("enabled", &P::enabled, "the safety layer between the controller and the wheels (on|off)");
    f("map", &P::map, "known (the floor plan and the range returns) | sensed (the returns alone)");
    f("margin", &P::margin, "protective field beyond the body: never entered while moving, m");
    f("reaction_time", &P::reaction_time, "added to the time needed to stop, s");
    f("slowdown_distance", &P::slowdown_distance,
      "slow-down field: within this gap of anything, speed is capped at slowdown_speed, m "
      "(0: off)");
    f("slowdown_speed", &P::slowdown_speed, "speed cap inside the slow-down field, m/s");
    f("person_margin", &P::person_margin, "extra room kept from people, m");
  }
};

}  // namespace floornav
