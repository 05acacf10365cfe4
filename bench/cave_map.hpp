#pragma once
// A cave-like occupancy map built in code, shaped like Stage's own benchmark world (the "cave"
// floorplan of Stage's worlds/simple.world: a 500 x 500 bitmap stretched over 16 x 16 m, so
// 0.032 m cells, with a wall all round and a few hollow blobs drawn as 1-2 cell outlines in a
// wide open hall). Long beams there mostly cross open floor, which is where a grid ray's cost
// used to grow with range. Fixed seed: the same map on every machine.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/world/occupancy_grid.hpp"

namespace floornav::bench {

constexpr int kCaveCells = 500;            // per side
constexpr double kCaveResolution = 0.032;  // m: 16 m / 500 cells

/// One hollow blob: a rounded box of half sizes (a, b) cells about (cx, cy), its outline wobbled
/// by two harmonics.
struct CaveBlob {
  double cx, cy, a, b, phase, wobble;
  /// Outline radius (cells) at angle `phi` from the centre.
  double radius(double phi) const {
    const double c = std::abs(std::cos(phi)), s = std::abs(std::sin(phi));
    // A superellipse of exponent 6 (a rounded rectangle).
    const double r = 1.0 / std::pow(std::pow(c / a, 6.0) + std::pow(s / b, 6.0), 1.0 / 6.0);
    return r * (1.0 + wobble * (std::sin(3.0 * phi + phase) + 0.5 * std::sin(7.0 * phi - phase)));
  }
  bool inside(double x, double y, double margin) const {
    const double dx = x - cx, dy = y - cy;
    return std::hypot(dx, dy) < radius(std::atan2(dy, dx)) + margin;
  }
};

struct CaveMap {
  std::shared_ptr<const OccupancyGrid> grid;
  std::vector<CaveBlob> blobs;
  /// True when world point `p` lies in the open hall: outside every blob (with a margin) and
  /// inside the outer wall.
  bool in_hall(const Vec2& p, double margin_m) const {
    const double x = p.x() / kCaveResolution, y = p.y() / kCaveResolution;
    const double m = margin_m / kCaveResolution;
    if (x < 1.0 + m || y < 1.0 + m || x > kCaveCells - 1.0 - m || y > kCaveCells - 1.0 - m)
      return false;
    for (const CaveBlob& b : blobs)
      if (b.inside(x, y, m + 2.0)) return false;
    return true;
  }
};

/// The map, origin (0, 0), yaw 0.
inline CaveMap make_cave_map() {
  CaveMap m;
  const int n = kCaveCells;
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(n) * n, 0);
  const auto mark = [&](int x, int y) {
    if (x >= 0 && y >= 0 && x < n && y < n) cells[static_cast<std::size_t>(y) * n + x] = 1;
  };
  for (int i = 0; i < n; ++i) {
    mark(i, 0), mark(i, n - 1), mark(0, i), mark(n - 1, i);
  }
  Rng rng(20261129);
  while (m.blobs.size() < 8) {
    CaveBlob b{rng.uniform(40.0, n - 40.0), rng.uniform(40.0, n - 40.0), rng.uniform(25.0, 70.0),
               rng.uniform(25.0, 45.0),     rng.uniform(0.0, 2.0 * kPi), rng.uniform(0.0, 0.04)};
    // Blobs keep 30 cells (~1 m) apart and clear of the outer wall; Stage's cave has one blob
    // that touches it, which changes nothing for rays.
    const double rb = std::max(b.a, b.b) * 1.1;
    bool fits =
        b.cx - rb > 20.0 && b.cy - rb > 20.0 && b.cx + rb < n - 20.0 && b.cy + rb < n - 20.0;
    for (const CaveBlob& o : m.blobs)
      fits = fits && std::hypot(o.cx - b.cx, o.cy - b.cy) > rb + std::max(o.a, o.b) * 1.1 + 30.0;
    if (!fits) continue;
    m.blobs.push_back(b);
    // The outline, sampled finely; each sample marks its cell and the one beside it: 1-2 cells.
    for (int k = 0; k < 8000; ++k) {
      const double phi = 2.0 * kPi * k / 8000.0;
      const double r = b.radius(phi);
      const double x = b.cx + r * std::cos(phi), y = b.cy + r * std::sin(phi);
      mark(static_cast<int>(x), static_cast<int>(y));
      mark(static_cast<int>(x + 0.6), static_cast<int>(y));
    }
  }
  m.grid = std::make_shared<const OccupancyGrid>(n, n, kCaveResolution, Pose2{Vec2(0.0, 0.0), 0.0},
                                                 std::move(cells));
  return m;
}

}  // namespace floornav::bench
