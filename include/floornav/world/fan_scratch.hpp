#pragma once
/// @file
/// The working memory of a fan of rays (World::cast_fan, OccupancyGrid::cast_fan), owned by the
/// caller.

#include <cstdint>
#include <vector>

namespace floornav {

/// Scratch buffers for casting fans of rays. A fan grows them to what it needs (its beams) and
/// leaves them for the next one, so a caller that keeps one FanScratch per thread (a robot's
/// sensing keeps one in its SensingScratch) casts fans without allocating after the first. The
/// contents mean nothing between calls; one FanScratch serves one thread at a time.
struct FanScratch {
  /// OccupancyGrid::cast_fan: the beams' directions in the grid frame, and each beam's nearest
  /// hit so far (cell units).
  std::vector<double> dx, dy, best;
};

}  // namespace floornav
