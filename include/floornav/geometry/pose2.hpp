#pragma once
/// @file
/// A planar pose: position and heading.

#include <cmath>

#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// Position (metres) and heading theta (radians, counter-clockwise from +x) of a body frame.
struct Pose2 {
  Vec2 position{Vec2::Zero()};
  double theta{0.0};

  /// Unit vector along the body's x axis, in the parent frame.
  Vec2 heading() const { return {std::cos(theta), std::sin(theta)}; }

  /// Maps a point from this body's frame to the parent frame.
  Vec2 transform_point(const Vec2& local) const { return position + rotate(local, theta); }

  /// Composes this pose with `child`, a pose given in this body's frame.
  Pose2 compose(const Pose2& child) const {
    return {transform_point(child.position), wrap_angle(theta + child.theta)};
  }

  /// The pose whose composition with this one is the identity.
  Pose2 inverse() const { return {-rotate(position, -theta), wrap_angle(-theta)}; }

  bool operator==(const Pose2& other) const {
    return position == other.position && theta == other.theta;
  }

  bool is_finite() const { return floornav::is_finite(position) && std::isfinite(theta); }
};

}  // namespace floornav
