#pragma once
/// @file
/// The four controller kinds, each a hybrid automaton over the behaviours of behaviours.hpp,
/// with the guards and resets of supervisor_guards.hpp (whose table lists every edge of the
/// complete automaton of Fig 5.11). Edges of a mode are tried in this order:
///   go_to_goal   GTG -> STOP (at_goal)
///   blended      BLEND -> STOP (at_goal); its flow is eq. 5.21
///   hard_switch  any -> STOP (at_goal); GTG -> AO (within_d_o); AO -> GTG (beyond_d_o)
///   hybrid       any -> STOP (at_goal); GTG -> AO (too_close); GTG -> FB-c, FB-cc
///                (obstacle_ahead); FB -> AO (too_close); FB -> GTG (progress_and_clear_shot,
///                boundary_lost); AO -> FB-c, FB-cc (resumes_following); AO -> GTG (safe_again)

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/geometry/vec2.hpp"
#include "floornav/nav/behaviours.hpp"
#include "floornav/nav/navigation_input.hpp"
#include "floornav/nav/navigation_params.hpp"
#include "floornav/nav/supervisor_guards.hpp"

namespace floornav {

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

}  // namespace floornav
