#pragma once
/// @file
/// A short memory of sensed obstacle points (world frame). A ring of five IR sensors sees a wall
/// only where its beams land; remembering the last second of returns lets follow-boundary round
/// a corner after the wall has slipped out of every beam. The world is static, so a remembered
/// point stays true; it is forgotten after `lifetime` seconds.

#include <array>
#include <span>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

class ObstacleMemory {
 public:
  static constexpr int kCapacity = 96;

  /// Adds `points` seen at time `t` (a point within `merge_radius` of a remembered one refreshes
  /// it), drops points older than `lifetime`, and writes all remembered points to `out`.
  /// Returns how many were written. No allocation.
  std::size_t update(std::span<const Vec2> points, double t, double lifetime, double merge_radius,
                     std::span<Vec2> out);

  void clear() { count_ = 0; }

 private:
  std::array<Vec2, kCapacity> points_{};
  std::array<double, kCapacity> times_{};
  int count_{0};
};

}  // namespace floornav
