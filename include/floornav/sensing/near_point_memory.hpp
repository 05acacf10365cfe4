#pragma once
/// @file
/// The range returns near a robot, kept for as long as they stay near: what a mapless safety
/// layer knows of the world outside its sensors' field of view (a 270 degree lidar is blind
/// behind; a robot backing up drives into that sector). The world it keeps is still: returns
/// on bodies that move are not added, so returns are added only within `add` of the robot,
/// where the caller knows every moving body. A return is forgotten once the robot is farther
/// than `keep` from it, not after a time, so a robot that waits still remembers.

#include <cstdint>
#include <span>
#include <vector>

#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/vec2.hpp"

namespace floornav {

class NearPointMemory {
 public:
  /// Points kept at most; a return that finds the memory full is not kept (it is in this step's
  /// scan, and is added again when room frees).
  static constexpr std::size_t kCapacity = 2048;

  /// `add` <= `keep`: m from the robot's centre within which returns are added, and kept;
  /// `cell`: m, the side of the squares of which each keeps one return (the first seen).
  NearPointMemory(double add, double keep, double cell);

  /// Forgets the points farther than `keep` from `centre`, adds `points` within `add` (a return
  /// inside one of `moving`, or in a square already held, is not added) and returns what is
  /// remembered. No allocation.
  std::span<const Vec2> update(std::span<const Vec2> points, const Vec2& centre,
                               std::span<const Circle> moving);

  std::span<const Vec2> points() const { return points_; }
  void clear();

 private:
  std::uint64_t key_of(const Vec2& p) const;
  /// The slot of `key` in the table: where it is, or the empty slot where it would go.
  std::size_t slot_of(std::uint64_t key) const;
  void refill_table();

  double add_;
  double keep_;
  double inv_cell_;
  std::vector<Vec2> points_;         ///< reserved kCapacity
  std::vector<std::uint64_t> keys_;  ///< the square of each point
  /// Open addressing over the squares held: index + 1 into points_, valid when its stamp is
  /// the current one (so that refilling needs no pass over the whole table; 0 is never current).
  std::vector<std::uint32_t> slot_index_;
  std::vector<std::uint32_t> slot_stamp_;
  std::uint32_t stamp_{1};
};

}  // namespace floornav
