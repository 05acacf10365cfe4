#pragma once
/// @file
/// A sampling planner on a raster: RRT-Connect (Kuffner & LaValle 2000) from OMPL, the robot a
/// disc in R^2, on the same inflated FreeRaster the A* planner searches (a state is valid when
/// its cell is free; a motion when `line_of_sight` holds on the raster). The target floornav::ompl
/// (built when CMake finds OMPL, option FLOORNAV_WITH_OMPL); linking it installs this search for
/// `planner.kind: rrt_connect` (nav/sampling_planner.hpp) before main() runs.
///
/// Why OMPL and not a hand-written RRT: it is the reference implementation (Debian's
/// libompl-dev), and only the validity checks are ours. OMPL stays behind this header:
/// floornav::ompl does not link it but loads it, from the module libfloornav_rrt_connect.so, on the
/// first call that needs a search, so that a program that never searches never pays for loading
/// OMPL.
///
/// Determinism: OMPL's RNGs are seeded from the process-wide seed generator unless told
/// otherwise, and `ompl::RNG::setSeed` works only once per process and before any RNG exists.
/// So every source of randomness of one plan is given its own RNG seeded from `seed`: the state
/// sampler (a RealVectorStateSampler whose RNG is reseeded) and the planner's own RNG; the trees'
/// nearest-neighbour structure is OMPL's SqrtApprox (deterministic; the default GNAT picks random
/// pivots). The budget is a count of planner iterations, not a time. Same raster, cells, seed and
/// budget: the same path, bit for bit, on any thread of any process.

#include <cstdint>
#include <vector>

#include "floornav/geometry/vec2.hpp"
#include "floornav/planning/free_raster.hpp"

namespace floornav {

/// RRT-Connect on `raster` from the centre of cell `start` to the centre of cell `goal` (both
/// must be free), drawing at most `max_samples` samples. Writes the path's vertices (cell units,
/// start and goal included; not simplified) to `out` and returns true; false, `out` empty, when
/// either cell is blocked, `max_samples` is below 1 or no path was found within the budget. A
/// SampledPathSearch. Precondition: `max_samples` <= kMaxRrtConnectSamples (planner_params.hpp),
/// the bound on a plan's time; above it std::invalid_argument is thrown before any work
/// (scenario validation refuses such a setting as bad input, and PlannerController too).
/// std::runtime_error, naming every place tried, when OMPL's module of this build cannot be
/// loaded (an incomplete install); the next call tries again.
bool rrt_connect_path(const FreeRaster& raster, GridCell start, GridCell goal, std::uint64_t seed,
                      int max_samples, std::vector<Vec2>& out);

}  // namespace floornav
