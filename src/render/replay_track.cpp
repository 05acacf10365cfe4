#include "replay_track.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

namespace floornav::render_detail {

namespace {

constexpr std::size_t kChunk = 4096;  ///< rows between two forced keeps

double wrapped(double a) {
  return std::remainder(a, 2.0 * std::numbers::pi);
}

bool finite_row(const TrajectorySample& s) {
  return std::isfinite(s.x) && std::isfinite(s.y) && std::isfinite(s.theta);
}

/// The row of (a, b) that the interpolation from a to b misses most, and by how much (in
/// tolerances: > 1 is too much).
std::pair<std::size_t, double> worst_row(std::span<const TrajectorySample> rows, std::size_t a,
                                         std::size_t b, const TrackTolerance& tol) {
  const TrajectorySample& p = rows[a];
  const TrajectorySample& q = rows[b];
  const double span = static_cast<double>(b - a);
  const double turn = wrapped(q.theta - p.theta);
  std::size_t worst = a;
  double worst_error = 0.0;
  for (std::size_t i = a + 1; i < b; ++i) {
    const TrajectorySample& s = rows[i];
    if (!finite_row(s)) return {i, 2.0};
    const double f = static_cast<double>(i - a) / span;
    const double dx = s.x - (p.x + f * (q.x - p.x));
    const double dy = s.y - (p.y + f * (q.y - p.y));
    const double dth = wrapped(s.theta - (p.theta + f * turn));
    const double error = std::max(std::hypot(dx, dy) / tol.position, std::abs(dth) / tol.heading);
    if (error > worst_error) {
      worst_error = error;
      worst = i;
    }
  }
  return {worst, worst_error};
}

}  // namespace

std::vector<std::size_t> decimate_track(std::span<const TrajectorySample> rows,
                                        const TrackTolerance& tol) {
  const std::size_t n = rows.size();
  std::vector<std::uint8_t> keep(n, 0);
  if (n == 0) return {};
  keep.front() = keep.back() = 1;
  for (std::size_t i = kChunk; i < n; i += kChunk) keep[i] = 1;
  std::vector<std::pair<std::size_t, std::size_t>> todo;
  std::size_t start = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (keep[i]) {
      todo.emplace_back(start, i);
      start = i;
    }
  while (!todo.empty()) {
    const auto [a, b] = todo.back();
    todo.pop_back();
    if (b <= a + 1) continue;
    const auto [i, error] = worst_row(rows, a, b, tol);
    if (error <= 1.0) continue;
    keep[i] = 1;
    todo.emplace_back(a, i);
    todo.emplace_back(i, b);
  }
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < n; ++i)
    if (keep[i]) kept.push_back(i);
  return kept;
}

}  // namespace floornav::render_detail
