#pragma once
/// @file
/// Raster line of sight: whether a straight segment crosses only free cells.

#include "floornav/geometry/vec2.hpp"
#include "floornav/planning/free_raster.hpp"

namespace floornav {

/// True when every cell whose closed square the segment a-b (cell units) touches is free: a
/// segment along a cell border needs the cells on both sides, one through a corner all four.
bool line_of_sight(const FreeRaster& raster, const Vec2& a, const Vec2& b);

}  // namespace floornav
