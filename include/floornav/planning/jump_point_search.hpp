#pragma once
/// @file
/// Jump point search (Harabor and Grastien 2011) on a FreeRaster: octile A*'s path length from
/// far fewer expansions on open floors.

#include <optional>

#include "floornav/planning/free_raster.hpp"

namespace floornav {

/// Jump point search: an octile path of the same length as octile_astar's (to the rounding of
/// the sums: 1e-12 relative), found by expanding only the jump points (straight runs to a
/// forced turn, diagonal runs to a straight run that finds one), tens of times fewer cells on
/// open floors. Where several paths are shortest, it may take another than octile_astar.
/// Empty when octile_astar's is. The search of scenario_optimum (runner/scenario_optimum.hpp).
std::optional<GridPath> octile_jump_point_search(const FreeRaster& raster, GridCell start,
                                                 GridCell goal);

}  // namespace floornav
