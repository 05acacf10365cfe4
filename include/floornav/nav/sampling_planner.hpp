#pragma once
/// @file
/// The sampling planner behind `planner.kind: rrt_connect`, as a hook: the core calls whatever
/// search is installed here and links no planning library itself. floornav::ompl installs OMPL's
/// RRT-Connect (floornav/ompl/rrt_connect.hpp) when a program links it, which a program linking
/// floornav::floornav does in a build with OMPL (FLOORNAV_WITH_OMPL). Without one installed,
/// validate_scenario refuses `planner.kind: rrt_connect` (bad input: exit status 2 in the CLI)
/// and a PlannerController asked for it throws InputError.

#include <cstdint>
#include <vector>

#include "floornav/geometry/vec2.hpp"
#include "floornav/planning/free_raster.hpp"

namespace floornav {

/// A sampling search on `raster` from the centre of cell `start` to the centre of cell `goal`
/// drawing at most `max_samples` samples from the stream `seed`: writes the path's vertices (cell
/// units, start and goal included) to `out` and returns true; false, `out` empty, when there is
/// none within the budget. The same arguments must give the same path, bit for bit.
using SampledPathSearch = bool (*)(const FreeRaster& raster, GridCell start, GridCell goal,
                                   std::uint64_t seed, int max_samples, std::vector<Vec2>& out);

/// Why `planner.kind: rrt_connect` is refused when no search is installed.
inline constexpr const char* kNoRrtConnect =
    "rrt_connect needs OMPL, and this program has no OMPL planner (floornav was built without "
    "OMPL: FLOORNAV_WITH_OMPL=OFF or Debian's libompl-dev not found; or the program does not "
    "link floornav::ompl); use astar";

/// The search `planner.kind: rrt_connect` runs; nullptr when none is installed.
SampledPathSearch rrt_connect_search();

/// Installs `search` for `planner.kind: rrt_connect` in this process (nullptr removes it).
/// floornav::ompl does this before main(); call it before runs start, not during them.
void set_rrt_connect_search(SampledPathSearch search);

}  // namespace floornav
