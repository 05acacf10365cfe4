#pragma once
/// @file
/// The lower envelope of parabolas along a line (Felzenszwalb & Huttenlocher, "Distance
/// Transforms of Sampled Functions", 2012): the exact 1-D squared distance transform that
/// OccupancyGrid's feature transform and DwaController's distance map share. An implementation
/// detail (namespace envelope_detail), public only because two layers use it.

#include <limits>

namespace floornav::envelope_detail {

/// The parabolas (x - q)^2 + f(q) of the sites q in [0, n) for which `is_site(q)` holds (it may
/// note f(q) for `intersect`); `intersect(p, q)` is where the parabolas of sites p < q cross,
/// written by each caller in its own arithmetic (the envelope depends on it only through its
/// comparisons). Calls `emit(x, q)` for every x in [0, n), in order, with the site q whose
/// parabola is lowest at x, and returns true; returns false, without a call, when there is no
/// site. `v` (n entries) and `z` (n + 1) are scratch. O(n).
template <class IsSite, class Intersect, class Emit>
bool lower_envelope(int n, IsSite&& is_site, Intersect&& intersect, Emit&& emit, int* v,
                    double* z) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  int k = -1;  // the envelope's last parabola: v[k] its site, z[k] where it starts to be lowest
  for (int q = 0; q < n; ++q) {
    if (!is_site(q)) continue;
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    double s = intersect(v[k], q);
    while (s <= z[k] && k > 0) s = intersect(v[--k], q);
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  if (k < 0) return false;
  k = 0;
  for (int x = 0; x < n; ++x) {
    while (z[k + 1] < x) ++k;
    emit(x, v[k]);
  }
  return true;
}

}  // namespace floornav::envelope_detail
