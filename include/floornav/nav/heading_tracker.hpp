#pragma once
/// @file
/// The differential-drive pipeline of Fig 5.12 (section 5.4.4): the automaton's velocity u for
/// the point robot becomes a heading reference theta_d = atan2(u_2, u_1), a PID turns the wrapped
/// heading error into omega, and V = |u| (capped).

#include "floornav/geometry/vec2.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/nav/pid.hpp"

namespace floornav {

/// Unicycle command that tracks velocity `u` (m/s, world frame) from heading `theta`.
/// With `slow_when_turning`, V is scaled by max(0, cos e) so the robot turns before it drives
/// when the heading error e is large (an extension; the chapter's V = |u| when false).
UnicycleCommand track_velocity(const Vec2& u, double theta, double v_max, const PidGains& gains,
                               PidState& pid, double dt, bool slow_when_turning);

}  // namespace floornav
