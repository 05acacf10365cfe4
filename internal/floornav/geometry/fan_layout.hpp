#pragma once
/// @file
/// Even fans of rays (a lidar's beams): the layout check shared by World::cast_fan,
/// OccupancyGrid::cast_fan and the sensors' fans over other robots (fan_cone.hpp culls). An
/// implementation detail (namespace fan_detail), public only because two layers share it.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>

#include "floornav/geometry/angle.hpp"

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace floornav::fan_detail {

constexpr double kTwoPi = 2.0 * kPi;

// Margin added on each side of an obstacle's angular extent: covers the float bounds of
// FanCone's table, the rounding of the directions and the tolerance on the
// beams' spacing by orders of magnitude.
constexpr double kFanMargin = 1e-4;    // rad
constexpr double kFanAngleTol = 1e-9;  // rad, beam angles against first + k * step

// Beam k of an even fan points at first + k * step (mod 2 pi), to within kFanAngleTol.
struct FanLayout {
  double first{0.0};
  double step{0.0};
  double inv_step{0.0};
  int n{0};
};

// Whether angle(i) lies within `tol` of first + i * step modulo 2 pi (of it or a turn either
// way: the angles are wrapped, the sum is not) for i = 1 .. n - 1; false for a NaN. Without
// branches or a reduction to one turn, and two beams at a time where SSE2 is: a few
// instructions a beam (a fan checks its beams at every step).
template <class Angle>
inline bool evenly_spaced(double first, double step, std::size_t n, Angle&& angle, double tol) {
  // |d| and |d -+ 2 pi| for the d of either sign: |d| and ||d| - 2 pi|.
  std::size_t i = 1;
  bool ok = true;
#if defined(__SSE2__)
  const __m128d vfirst = _mm_set1_pd(first), vstep = _mm_set1_pd(step);
  const __m128d two_pi = _mm_set1_pd(kTwoPi), vtol = _mm_set1_pd(tol), sign = _mm_set1_pd(-0.0);
  __m128d index = _mm_set_pd(2.0, 1.0);  // (low, high) lanes: beams i, i + 1
  __m128d good = _mm_cmpeq_pd(vtol, vtol);
  for (; i + 1 < n; i += 2) {
    const __m128d v = _mm_set_pd(angle(i + 1), angle(i));
    const __m128d a =
        _mm_andnot_pd(sign, _mm_sub_pd(v, _mm_add_pd(vfirst, _mm_mul_pd(index, vstep))));
    const __m128d b = _mm_andnot_pd(sign, _mm_sub_pd(a, two_pi));
    good = _mm_and_pd(good, _mm_cmple_pd(_mm_min_pd(a, b), vtol));  // a NaN compares false
    index = _mm_add_pd(index, _mm_set1_pd(2.0));
  }
  ok = _mm_movemask_pd(good) == 3;
#endif
  for (; i < n; ++i) {
    const double a = std::abs(angle(i) - (first + static_cast<double>(i) * step));
    ok &= std::min(a, std::abs(a - kTwoPi)) <= tol;
  }
  return ok;
}

// The layout of `angles` when they are evenly spaced counter-clockwise and do not overlap
// themselves after a full turn; nullopt otherwise. With `spacing_known` (the caller knows every
// angle is within kFanAngleTol of first + k * step, as a SensorLayout lidar's are), the per-angle
// check is skipped: the layout is read from the first two.
inline std::optional<FanLayout> even_fan(std::span<const double> angles,
                                         bool spacing_known = false) {
  const std::size_t n = angles.size();
  if (n < 2 || n > (1u << 24)) return std::nullopt;
  FanLayout f;
  f.first = angles[0];
  f.step = angles[1] - angles[0];
  if (f.step < 0.0) f.step += kTwoPi;
  f.n = static_cast<int>(n);
  if (!(f.step > 1e-6) || !((n - 1) * f.step <= kTwoPi - 0.5 * f.step)) return std::nullopt;
  f.inv_step = 1.0 / f.step;
  if (!spacing_known &&
      !evenly_spaced(
          f.first, f.step, n, [&](std::size_t i) { return angles[i]; }, kFanAngleTol))
    return std::nullopt;
  return f;
}

// floor by truncation to an integer: x86-64 before SSE4.1 has no rounding instruction, so
// std::floor is a dozen instructions, and the fans take it per obstacle and per tile. The same
// values (but the sign of a zero result), NaN and huge values included.
inline double floor_by_truncation(double x) {
  if (!(std::abs(x) < 0x1p52)) return std::floor(x);  // an integer already, or NaN
  const double t = static_cast<double>(static_cast<long long>(x));
  return t > x ? t - 1.0 : t;
}

}  // namespace floornav::fan_detail
