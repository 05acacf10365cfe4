#pragma once
// Cell lookup shared by World's spatial index and OccupancyGrid. Internal to src/world.

namespace floornav::cell_detail {

// clamp(floor(v), 0, n - 1) without a call to floor(): for 0 <= v < n, truncation is the floor.
// The same cell for every v (NaN and anything below 0 give cell 0, anything from n up n - 1).
inline int clamp_cell(double v, int n) {
  if (!(v >= 0.0)) return 0;
  if (v >= n) return n - 1;
  return static_cast<int>(v);
}

}  // namespace floornav::cell_detail
