#pragma once
/// @file
/// Rectangles turned in the plane: the footprints of moving machines (forklifts) that range
/// sensors see and robots must not touch.

#include <array>
#include <optional>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// A solid rectangle of half-sizes `half` (along its heading, across it), centred at `center`,
/// turned by `heading` (rad, counter-clockwise). `axis` is (cos heading, sin heading).
struct OrientedBox {
  Vec2 center{Vec2::Zero()};
  Vec2 half{Vec2::Zero()};  ///< m, half length and half width, >= 0
  Vec2 axis{1.0, 0.0};      ///< unit vector along the length

  static OrientedBox make(const Vec2& center, const Vec2& size, double heading);
  /// `p` (world) in the box's frame: along its length, across it.
  Vec2 to_local(const Vec2& p) const {
    const Vec2 d = p - center;
    return {d.dot(axis), cross(axis, d)};
  }
  /// The radius of the disc round the centre that holds the box.
  double bounding_radius() const { return half.norm(); }
  /// The four corners, counter-clockwise.
  std::array<Vec2, 4> corners() const;
};

/// Signed distance from `p` to the box's boundary: negative inside.
double signed_distance(const OrientedBox& b, const Vec2& p);

/// Distance along the ray `origin + t dir` (unit `dir`) to the box's boundary, `t >= 0`; 0 when
/// the origin is inside (the slab test in the box's frame).
std::optional<double> intersect_ray(const OrientedBox& b, const Vec2& origin, const Vec2& dir);

}  // namespace floornav
