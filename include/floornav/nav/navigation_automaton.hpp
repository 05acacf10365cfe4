#pragma once
/// @file
/// The four controller kinds, each a hybrid automaton over the behaviours of behaviours.hpp.
/// `hybrid` is the complete automaton of Fig 5.11:
///
///   any      -> STOP    |x - x_g| < epsilon
///   GTG      -> AO      clearance < d_unsafe
///   GTG      -> FB-c    clearance < d_o, obstacle in the way (<u_AO, u_GTG> <= 0) and
///                       <u_GTG, u_FB^c> > 0 (eq. 5.23); reset d_tau := |x - x_g|
///   GTG      -> FB-cc   the same with <u_GTG, u_FB^cc> > 0 (eq. 5.24)
///   FB       -> AO      clearance < d_unsafe
///   FB       -> GTG     progress |x - x_g| < d_tau - delta (eqs. 5.25/5.26) and
///                       clear shot <u_AO, u_GTG> > 0 (eq. 5.27); or the boundary is lost
///   AO       -> FB      clearance >= d_unsafe + hysteresis, back in the direction it left
///   AO       -> GTG     clearance >= d_unsafe + hysteresis with a clear shot, when AO was
///                       entered from GTG

#include <limits>
#include <span>

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/geometry/vec2.hpp"
#include "floornav/nav/behaviours.hpp"
#include "floornav/nav/navigation_params.hpp"

namespace floornav {

/// What the supervisor sees at one step, computed once from the sensed points.
struct NavigationInput {
  Vec2 x{Vec2::Zero()};      ///< robot position, m
  Vec2 goal{Vec2::Zero()};   ///< current goal, m
  Vec2 u_gtg{Vec2::Zero()};  ///< eq. 5.18
  Vec2 u_ao{Vec2::Zero()};   ///< eq. 5.20; zero when no obstacle is sensed
  Vec2 away{Vec2::Zero()};   ///< u_AO normalised
  double clearance{std::numeric_limits<double>::infinity()};  ///< nearest sensed, from the body
  double goal_distance{0.0};                                  ///< |x - x_g|
  bool obstacle_sensed{false};
  /// A sensed point lies in the corridor towards the goal (NavigationParams::clear_shot_corridor;
  /// false when that test is off).
  bool corridor_blocked{false};
};

/// The automaton's memory, written only by resets.
struct NavigationMemory {
  double d_tau{std::numeric_limits<double>::infinity()};  ///< |x - x_g| when FB was entered
  Turn turn{Turn::Clockwise};                             ///< the direction FB took
  bool following{false};  ///< inside a boundary-following episode (FB or AO from FB)
};

using NavigationAutomaton = HybridAutomaton<NavigationInput, NavigationMemory, Vec2>;

/// Mode names as they appear in summaries, CSV and pictures.
namespace mode_names {
inline constexpr const char* kGoToGoal = "go_to_goal";
inline constexpr const char* kAvoidObstacle = "avoid_obstacle";
inline constexpr const char* kFollowCw = "follow_boundary_cw";
inline constexpr const char* kFollowCcw = "follow_boundary_ccw";
inline constexpr const char* kBlended = "blended";
inline constexpr const char* kStop = "stop";
}  // namespace mode_names

/// Builds the automaton of `kind` (validated and frozen).
NavigationAutomaton make_navigation_automaton(ControllerKind kind, const NavigationParams& p);

/// A robot's footprint polygon (robot frame) and heading, for guards that measure clearance from
/// the footprint (NavigationParams::footprint_clearance).
struct BodyShape {
  std::span<const Vec2> footprint;
  double heading{0.0};  ///< rad
};

/// The step's input from the robot position, goal and sensed obstacle points (world frame).
/// The clearance is from the body disc of `body_radius`, or, with `shape` given and
/// `p.footprint_clearance` on, from the footprint polygon.
NavigationInput make_navigation_input(const Vec2& x, const Vec2& goal,
                                      std::span<const Vec2> obstacle_points, double body_radius,
                                      const NavigationParams& p, const BodyShape* shape = nullptr);

}  // namespace floornav
