#pragma once
/// @file
/// Robot-robot avoidance's parameters (nav/robot_avoidance.hpp): the keys `robot_avoidance`,
/// `avoidance_range`, `avoidance_horizon`, `avoidance_margin` and `avoidance_neighbours` of a
/// `controller:` section.

#include <span>

#include "floornav/core/enum_names.hpp"

namespace floornav {

/// How a robot avoids the other robots of its fleet.
enum class RobotAvoidance {
  None,  ///< the chapter: other robots are obstacles like any other
  Orca,  ///< a reciprocal-velocity layer between the controller's command and the wheels
};

inline constexpr EnumName<RobotAvoidance> kRobotAvoidanceNames[]{{RobotAvoidance::None, "none"},
                                                                 {RobotAvoidance::Orca, "orca"}};
constexpr std::span<const EnumName<RobotAvoidance>> enum_names(RobotAvoidance) {
  return kRobotAvoidanceNames;
}

struct RobotAvoidanceParams {
  RobotAvoidance kind{RobotAvoidance::Orca};
  double range{1.0};    ///< m between centres: robots told to this one (NearbyRobot)
  double horizon{2.0};  ///< s: ORCA's time horizon tau for other robots
  double margin{0.02};  ///< m added to the sum of two robots' radii
  /// ORCA takes this many of the moving robots told, the nearest (RVO2's maxNeighbors: its
  /// examples use 10); the safety layer still keeps clear of every one.
  int neighbours{10};

  bool operator==(const RobotAvoidanceParams&) const = default;

  /// Lists every field once, with its key and doc (core/param_fields.hpp).
  template <class Fields>
  static void fields(Fields& f) {
    using P = RobotAvoidanceParams;
    f("robot_avoidance", &P::kind,
      "none (other robots are obstacles) | orca (a reciprocal-velocity layer)");
    f("avoidance_range", &P::range,
      "robot_avoidance: other robots within this distance (centres) are avoided, m");
    f("avoidance_horizon", &P::horizon, "robot_avoidance orca: time horizon tau, s");
    f("avoidance_margin", &P::margin,
      "robot_avoidance orca: added to the sum of two robots' radii, m");
    f("avoidance_neighbours", &P::neighbours,
      "robot_avoidance orca: the nearest moving robots avoided by velocity (at most)");
  }
};

}  // namespace floornav
