#pragma once
/// @file
/// Exact integration of the unicycle model (eqs. 5.7-5.9) over one step.

#include "floornav/geometry/pose2.hpp"
#include "floornav/kinematics/differential_drive.hpp"

namespace floornav {

/// The pose after driving `u` for `dt` seconds from `pose`: x' = V cos(theta),
/// y' = V sin(theta), theta' = omega (eqs. 5.7-5.9), integrated exactly along the circular arc
/// (a straight line when omega is 0), not by an Euler step.
Pose2 integrate_unicycle(const Pose2& pose, const UnicycleCommand& u, double dt);
/// `integrate_unicycle` with `heading` = (cos, sin) of `pose.theta` already taken by the caller
/// (e.g. for its sensors at the same pose): the same pose, bit for bit, without a sine and cosine.
Pose2 integrate_unicycle(const Pose2& pose, const UnicycleCommand& u, double dt,
                         const Vec2& heading);

}  // namespace floornav
