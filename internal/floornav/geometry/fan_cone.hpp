#pragma once
/// @file
/// The beams of an even fan that point into a cone of directions, found with one division per
/// direction and a table instead of an atan2 per direction. An implementation detail (namespace
/// fan_detail), public only because two layers share it.

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "floornav/geometry/fan_layout.hpp"

namespace floornav::fan_detail {

// The "diamond angle" of (x, y) != (0, 0): a number in [0, 4] that grows with the angle of
// (x, y) over [0, 2 pi) (0 along +x, 1 along +y, 2 along -x, 3 along -y): where the ray through
// (x, y) crosses the diamond |x| + |y| = 1, counted along it.
inline double diamond_angle(double x, double y) {
  const double p = y / (std::abs(x) + std::abs(y));
  return x < 0.0 ? 2.0 - p : (y < 0.0 ? 4.0 + p : p);
}

// Diamond angles [4 j / kDiamondBins, 4 (j + 1) / kDiamondBins) make bin j. A bin spans at most
// 8 / kDiamondBins rad (0.0039 rad: a fifth of a 1-degree beam spacing), and the table takes
// 8 KB: more bins cull a little more for a table twice the size. The instructions of
// BM_CaveGridCastFanHalfTurn180 (bench/grid_bench.cpp) under callgrind decide the size.
constexpr int kDiamondBins = 2048;

// diamond_bounds()[j]: the angle (rad, in [0, 2 pi]) of diamond angle 4 j / kDiamondBins, so bin j
// holds the angles [bounds[j], bounds[j + 1]] (to within float rounding, 3e-7 rad).
inline const std::array<float, kDiamondBins + 1>& diamond_bounds() {
  static const std::array<float, kDiamondBins + 1> bounds = [] {
    std::array<float, kDiamondBins + 1> b{};
    for (int j = 0; j <= kDiamondBins; ++j) {
      // The point of the diamond at diamond angle p (see diamond_angle).
      const double p = 4.0 * j / kDiamondBins;
      double x = 0.0, y = 0.0;
      if (p <= 1.0) {
        x = 1.0 - p, y = p;
      } else if (p <= 3.0) {
        y = 2.0 - p, x = -(1.0 - std::abs(y));
      } else {
        y = p - 4.0, x = 1.0 - std::abs(y);
      }
      double a = std::atan2(y, x);
      if (a < 0.0 || (j == kDiamondBins && a == 0.0)) a += kTwoPi;
      b[static_cast<std::size_t>(j)] = static_cast<float>(a);
    }
    return b;
  }();
  return bounds;
}

// The beams of `fan` (angles in one frame) by direction vectors given in another, turned by
// `frame_yaw` from it (a vector at angle a there is at a + frame_yaw in the fan's frame).
class FanCone {
 public:
  FanCone(const FanLayout& fan, double frame_yaw) : fan_(fan), bounds_(diamond_bounds().data()) {
    // The angle of beam 0 in the vectors' frame, in [0, 2 pi).
    double first = fan.first - frame_yaw;
    first -= kTwoPi * floor_by_truncation(first * (1.0 / kTwoPi));
    first_ = first < kTwoPi ? first : 0.0;
  }

  // Calls f(k) for every beam k whose angle may lie in the cone from direction (cw_x, cw_y)
  // counter-clockwise to (ccw_x, ccw_y) (less than a half turn wide; neither vector zero),
  // widened by kFanMargin on each side, and possibly a few more (within a bin of its edges).
  // When f returns bool, true stops the calls: then for_beams returns whether one did.
  template <class F>
  bool for_beams(double cw_x, double cw_y, double ccw_x, double ccw_y, F&& f) const {
    return for_each_beam(spans_between(cw_x, cw_y, ccw_x, ccw_y), f);
  }

  // The beams for_beams calls f for, as at most two intervals: g(k0, k1) for each, beams k0 to
  // k1 (k0 <= k1), for callers that test several beams at once.
  template <class G>
  void for_spans(double cw_x, double cw_y, double ccw_x, double ccw_y, G&& g) const {
    call_spans(spans_between(cw_x, cw_y, ccw_x, ccw_y), g);
  }

  // The same for the beams within `half` (in [0, pi]) of the direction of (x, y) (not zero).
  template <class F>
  bool for_beams_about(double x, double y, double half, F&& f) const {
    return for_each_beam(spans_about(x, y, half), f);
  }

  // The beams for_beams_about calls f for, as at most two intervals: g(k0, k1) for each, beams
  // k0 to k1 (k0 <= k1), for callers that test several beams at once.
  template <class G>
  void for_spans_about(double x, double y, double half, G&& g) const {
    call_spans(spans_about(x, y, half), g);
  }

 private:
  // The beams at angles [lo, hi] from beam 0, modulo 2 pi (lo >= -4 pi, hi >= lo): k0 to k1,
  // then, past beam 0 again (a turn later), 0 to wrap_last (below k0; -1 for none).
  struct Spans {
    int k0, k1, wrap_last;
  };
  Spans spans(double lo, double hi) const {
    while (lo < 0.0) lo += kTwoPi, hi += kTwoPi;
    // Beam k (k >= 0) is at k * step; lo >= 0, so truncation is floor.
    const double a = lo * fan_.inv_step, z = hi * fan_.inv_step;
    int k0 = static_cast<int>(a);
    if (k0 < a) ++k0;
    const int k1 = static_cast<int>(std::min(z, fan_.n - 1.0));
    int wrap_last = -1;
    if (hi >= kTwoPi) {
      const int k2 = static_cast<int>(std::min((hi - kTwoPi) * fan_.inv_step, fan_.n - 1.0));
      wrap_last = std::min(k2, k0 - 1);
    }
    return {k0, k1, wrap_last};
  }

  template <class G>
  static void call_spans(const Spans& s, G&& g) {
    if (s.k0 <= s.k1) g(s.k0, s.k1);
    if (s.wrap_last >= 0) g(0, s.wrap_last);
  }

  // The spans of the beams in the cone from (cw_x, cw_y) counter-clockwise to (ccw_x, ccw_y).
  Spans spans_between(double cw_x, double cw_y, double ccw_x, double ccw_y) const {
    const int b0 = bin(cw_x, cw_y), b1 = bin(ccw_x, ccw_y);
    // The cone's angles from beam 0.
    const double lo = static_cast<double>(bounds_[b0]) - first_ - kFanMargin;
    double hi = static_cast<double>(bounds_[b1 + 1]) - first_ + kFanMargin;
    if (b1 < b0) hi += kTwoPi;  // through angle 0 of the vectors' frame
    return spans(lo, hi);
  }

  // The spans of the beams within `half` of the direction of (x, y).
  Spans spans_about(double x, double y, double half) const {
    const int b = bin(x, y);
    const double lo = static_cast<double>(bounds_[b]) - first_ - half - kFanMargin;
    const double hi = static_cast<double>(bounds_[b + 1]) - first_ + half + kFanMargin;
    return spans(lo, hi);
  }

  // f(k) for each beam of `s` in order; when f returns bool, true stops the calls (and is
  // returned).
  template <class F>
  static bool for_each_beam(const Spans& s, F&& f) {
    const auto [k0, k1, wrap_last] = s;
    const auto call = [&](int k) {
      if constexpr (std::is_same_v<decltype(f(k)), bool>) {
        return f(k);
      } else {
        f(k);
        return false;
      }
    };
    for (int k = k0; k <= k1; ++k)
      if (call(k)) return true;
    for (int k = 0; k <= wrap_last; ++k)
      if (call(k)) return true;
    return false;
  }

  static int bin(double x, double y) {
    const int b = static_cast<int>(diamond_angle(x, y) * (kDiamondBins / 4.0));
    return std::min(b, kDiamondBins - 1);
  }

  FanLayout fan_;
  const float* bounds_;
  double first_{0.0};
};

}  // namespace floornav::fan_detail
