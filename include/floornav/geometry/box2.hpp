#pragma once
/// @file
/// Axis-aligned boxes: the bounds of a world, of an obstacle, of a spatial index.

#include <span>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// Axis-aligned box `[min, max]` (metres).
struct Box2 {
  Vec2 min{Vec2::Zero()};
  Vec2 max{Vec2::Zero()};

  bool contains(const Vec2& p) const {
    return p.x() >= min.x() && p.x() <= max.x() && p.y() >= min.y() && p.y() <= max.y();
  }
  Vec2 size() const { return max - min; }
};

/// The smallest box holding the points `pts` (not empty).
inline Box2 box_of(std::span<const Vec2> pts) {
  Box2 b{pts[0], pts[0]};
  for (const Vec2& p : pts) {
    b.min = b.min.cwiseMin(p);
    b.max = b.max.cwiseMax(p);
  }
  return b;
}

}  // namespace floornav
