#pragma once
/// @file
/// The guards and resets of the chapter's automaton (Fig 5.11) and of hard switching (Fig 5.7),
/// each a named function citing its equation. The automata (navigation_automaton.hpp) are built
/// from them; a user's own supervisor may reuse them.
///
///   function (name in outputs)          edge                 condition
///   at_goal (at_goal)                   any -> STOP          |x - x_g| < epsilon
///   too_close (too_close)               GTG, FB -> AO        clearance < d_unsafe
///   obstacle_ahead(turn)                GTG -> FB-c / FB-cc  clearance < d_o, no clear shot,
///     (obstacle_ahead_cw, _ccw)                              and the turn of eqs. 5.23/5.24;
///                                                            reset start_following
///   progress_and_clear_shot (same)      FB -> GTG            |x - x_g| < d_tau - delta
///                                                            (eqs. 5.25/5.26) and a clear
///                                                            shot (eq. 5.27); reset
///                                                            stop_following
///   boundary_lost (boundary_lost)       FB -> GTG            nothing sensed any more; reset
///                                                            stop_following
///   resumes_following(turn)             AO -> FB-c / FB-cc   safe again (clearance >=
///     (safe_again_cw, safe_again_ccw)                        d_unsafe + hysteresis), back in
///                                                            the episode's direction, or a
///                                                            fresh episode's choice; reset
///                                                            resume_following
///   safe_again (safe_again_clear_shot)  AO -> GTG            clearance >= d_unsafe + hysteresis
///   within_d_o, beyond_d_o              GTG <-> AO (Fig 5.7) clearance < d_o / >= d_o
///     (obstacle_within_d_o, obstacle_beyond_d_o)

#include <limits>

#include "floornav/nav/behaviours.hpp"
#include "floornav/nav/navigation_input.hpp"
#include "floornav/nav/navigation_params.hpp"

namespace floornav {

/// The automaton's memory, written only by resets.
struct NavigationMemory {
  double d_tau{std::numeric_limits<double>::infinity()};  ///< |x - x_g| when FB was entered
  Turn turn{Turn::Clockwise};                             ///< the direction FB took
  bool following{false};  ///< inside a boundary-following episode (FB or AO from FB)
};

namespace guards {

/// any -> STOP: |x - x_g| < epsilon.
bool at_goal(const NavigationInput& in, const NavigationParams& p);
/// GTG, FB -> AO: the obstacle is closer than d_unsafe.
bool too_close(const NavigationInput& in, const NavigationParams& p);
/// AO -> FB, GTG: back at d_unsafe + hysteresis (a fat guard: AO is entered below d_unsafe).
bool safe_again(const NavigationInput& in, const NavigationParams& p);
/// Eq. 5.27: a clear shot at the goal, <u_AO, u_GTG> > 0; with the corridor extension on
/// (clear_shot_corridor > 0), a free corridor of the body's width towards the goal instead.
bool clear_shot(const NavigationInput& in, const NavigationParams& p);
/// GTG -> FB-c / FB-cc: an obstacle met at d_o that is in the way (no clear shot: the course's
/// "sliding" condition), and `turn` is the direction eqs. 5.23/5.24 choose.
bool obstacle_ahead(const NavigationInput& in, const NavigationParams& p, Turn turn);
/// FB -> GTG: progress made, |x - x_g| < d_tau - delta (eqs. 5.25/5.26), and a clear shot
/// (eq. 5.27).
bool progress_and_clear_shot(const NavigationInput& in, const NavigationMemory& m,
                             const NavigationParams& p);
/// FB -> GTG: the boundary slipped out of every sensor.
bool boundary_lost(const NavigationInput& in);
/// AO -> FB-c / FB-cc: safe again and back in the direction the episode took; outside an
/// episode (AO entered from GTG), an obstacle in the way and the turn of eqs. 5.23/5.24.
bool resumes_following(const NavigationInput& in, const NavigationMemory& m,
                       const NavigationParams& p, Turn turn);
/// Fig 5.7, GTG -> AO: the obstacle is within d_o.
bool within_d_o(const NavigationInput& in, const NavigationParams& p);
/// Fig 5.7, AO -> GTG: the obstacle is at d_o or beyond.
bool beyond_d_o(const NavigationInput& in, const NavigationParams& p);

}  // namespace guards

namespace resets {

/// The reset of Fig 5.11 on entering follow-boundary at time tau: d_tau := |x(tau) - x_g|, and
/// the direction taken.
void start_following(const NavigationInput& in, NavigationMemory& m, Turn turn);
/// AO -> FB: the episode goes on in `turn`; a fresh episode (AO entered from GTG) stores d_tau as
/// start_following does.
void resume_following(const NavigationInput& in, NavigationMemory& m, Turn turn);
/// FB -> GTG: the episode is over.
void stop_following(NavigationMemory& m);

}  // namespace resets

}  // namespace floornav
