#pragma once
/// @file
/// Greedy string pulling: a polyline shortened by dropping the vertices a line of sight sees past.

#include <cstddef>
#include <span>
#include <vector>

#include "floornav/geometry/vec2.hpp"
#include "floornav/planning/free_raster.hpp"

namespace floornav {

/// Greedy string pulling: drops every vertex of the polyline `points` (cell units) that the
/// previous kept vertex can see past (`line_of_sight` on `raster`). The result is never longer
/// than the input, and its segments cross only free cells when the input's do.
std::vector<Vec2> pull_string(const FreeRaster& raster, std::span<const Vec2> points);

/// The same greedy string pulling with any line-of-sight test `clear(a, b)` (a planner's test
/// on the world's clearance, say), in whatever frame the points are. Written to `out`.
template <class LineOfSight>
void pull_string(std::span<const Vec2> points, LineOfSight&& clear, std::vector<Vec2>& out) {
  out.clear();
  if (points.empty()) return;
  out.push_back(points[0]);
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
    if (!clear(out.back(), points[i + 1])) out.push_back(points[i]);
  if (points.size() > 1) out.push_back(points.back());
}

}  // namespace floornav
