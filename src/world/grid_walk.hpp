#pragma once
// What OccupancyGrid's ray walk, its distance transform and its fan share. Internal to
// src/world.

#include <cstdint>
#include <limits>

namespace floornav::grid_detail {

constexpr double kInf = std::numeric_limits<double>::infinity();

// free_run_ counts in 1/16 cell, up to 4096 cells; a jump shorter than a cell is not worth it.
constexpr double kFreeRunUnits = 16.0;
constexpr std::uint16_t kMaxFreeRun = 65535;
constexpr int kMinJump = 16;

// The boundary events of a walk on one axis (Amanatides & Woo, "A Fast Voxel Traversal Algorithm
// for Ray Tracing", 1987), in cell units: a ray at coordinate `o` moving by `d` per unit of t
// (sign `step`) leaves line i (column or row) at exit(i). Each time is computed afresh from the
// integer boundary and the ray's origin, so no error accumulates along long rays, and every walk
// computes the very same quotients.
struct BoundaryTimes {
  double o;
  double d;
  int step;
  double exit(int i) const { return step > 0 ? (i + 1 - o) / d : (step < 0 ? (i - o) / d : kInf); }
};

}  // namespace floornav::grid_detail
