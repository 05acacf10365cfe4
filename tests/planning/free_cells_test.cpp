// The free cells of a disc robot on a raster of a world, against one clearance query per cell.
#include "floornav/planning/free_cells.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

// free_cells skips queries by the 1-Lipschitz bound; it must give the raster of one query per cell.
TEST(FreeCells, EqualsOneClearanceQueryPerCell) {
  WorldDesc d;
  d.bounds = Box2{{-1.0, -1.0}, {6.0, 4.0}};
  d.circles = {Circle{{1.0, 1.0}, 0.4}, Circle{{4.0, 2.5}, 0.05}, Circle{{2.5, 0.2}, 0.0}};
  d.polygons = {{{2.0, 2.0}, {3.0, 2.2}, {2.6, 3.1}}, {{4.5, -0.5}, {5.5, -0.5}, {5.5, 1.5}}};
  const World w(d);
  for (const double r : {0.0, 0.05, 0.1, 0.37}) {
    for (const Pose2& origin : {Pose2{{-1.3, -1.2}, 0.0}, Pose2{{0.7, -2.0}, 0.6}}) {
      const FreeRaster f = free_cells(w, r, origin, 0.05, 150, 110);
      ASSERT_EQ(f.free.size(), 150u * 110u);
      std::size_t mismatches = 0, free = 0;
      for (int iy = 0; iy < 110; ++iy)
        for (int ix = 0; ix < 150; ++ix) {
          const Vec2 c = origin.transform_point(Vec2((ix + 0.5) * 0.05, (iy + 0.5) * 0.05));
          const bool expect = w.clearance(c) > r;
          mismatches += f.is_free(ix, iy) != expect;
          free += expect;
        }
      EXPECT_EQ(mismatches, 0u) << "r " << r;
      EXPECT_GT(free, 1000u);
    }
  }
  // An occupancy map with a wall, at its own cells.
  std::vector<std::uint8_t> occ(40 * 30, 0);
  for (int y = 3; y < 27; ++y) occ[static_cast<std::size_t>(y) * 40 + 17] = 1;
  const OccupancyGrid g(40, 30, 0.1, Pose2{{2.0, 1.0}, 0.3}, std::move(occ));
  WorldDesc gd;
  gd.grid = std::make_shared<const OccupancyGrid>(g);
  const World gw(gd);
  const FreeRaster f = free_cells(gw, 0.25, g.origin(), 0.1, 40, 30);
  for (int iy = 0; iy < 30; ++iy)
    for (int ix = 0; ix < 40; ++ix) {
      const Vec2 c = g.origin().transform_point(Vec2((ix + 0.5) * 0.1, (iy + 0.5) * 0.1));
      ASSERT_EQ(f.is_free(ix, iy), gw.clearance(c) > 0.25) << ix << ", " << iy;
    }
  EXPECT_TRUE(free_cells(gw, 0.25, g.origin(), 0.1, 0, 30).free.empty());
}

// The raster is built from the obstacles near each cell (and the grid's distance transform), not
// by a query per cell: on random worlds it must still be, cell for cell, what a clearance query at
// each centre says (the brute-force query: World::clearance's ring search can stop early for a
// centre outside the obstacles' index box, in a world without bounds). Worlds: polygons, circles
// (some points), bounds or none, an occupancy grid with yaw or none; frames rotated or not, the
// grid's own or another; radii 0 to 0.4 m, and radii equal to a centre's clearance (the tie, where
// `> r` decides).
TEST(FreeCells, RandomWorldsEqualOneClearanceQueryPerCell) {
  Rng rng(20261129);
  std::size_t cells = 0, free_cells_seen = 0;
  for (int trial = 0; trial < 60; ++trial) {
    WorldDesc d;
    if (trial % 3 != 2)
      d.bounds = Box2{{-1.0, -1.0}, {rng.uniform(2.0, 5.0), rng.uniform(2.0, 4.0)}};
    const int polygons = static_cast<int>(rng.uniform(0.0, 6.0));
    for (int k = 0; k < polygons; ++k) {
      const Vec2 c(rng.uniform(-0.5, 3.0), rng.uniform(-0.5, 2.5));
      std::vector<Vec2> poly;
      const int n = 3 + static_cast<int>(rng.uniform(0.0, 5.0));
      for (int i = 0; i < n; ++i) {
        const double a = 2.0 * std::numbers::pi * (i + rng.uniform(0.0, 0.8)) / n;
        const double rad = rng.uniform(0.1, 0.6);
        poly.emplace_back(c.x() + rad * std::cos(a), c.y() + rad * std::sin(a));
      }
      d.polygons.push_back(poly);
    }
    const int circles = static_cast<int>(rng.uniform(0.0, 4.0));
    for (int k = 0; k < circles; ++k)
      d.circles.push_back(
          {{rng.uniform(-0.5, 3.0), rng.uniform(-0.5, 2.5)}, k == 0 ? 0.0 : rng.uniform(0.0, 0.4)});
    const bool with_grid = trial % 4 == 1;
    if (with_grid) {
      const int gw = 30 + static_cast<int>(rng.uniform(0.0, 20.0)), gh = 25;
      std::vector<std::uint8_t> occ(static_cast<std::size_t>(gw * gh), 0);
      for (auto& o : occ) o = rng.uniform() < 0.05;
      d.grid = std::make_shared<const OccupancyGrid>(
          gw, gh, 0.1,
          Pose2{{rng.uniform(-1.5, -0.5), rng.uniform(-1.5, -0.5)}, rng.uniform(-0.5, 0.5)},
          std::move(occ));
    }
    if (d.polygons.empty() && d.circles.empty() && !d.bounds && !d.grid)
      d.bounds = Box2{{0, 0}, {2, 2}};
    const World w(d);
    // The grid's own frame (as scenario_optimum uses it), or a frame of its own.
    const bool own = with_grid && trial % 8 == 1;
    const Pose2 origin = own ? d.grid->origin()
                             : Pose2{{rng.uniform(-1.6, -0.8), rng.uniform(-1.6, -0.8)},
                                     trial % 2 ? rng.uniform(-1.0, 1.0) : 0.0};
    const double cell = own ? 0.1 : rng.uniform(0.03, 0.09);
    const int width = own ? d.grid->width() : static_cast<int>(rng.uniform(40.0, 110.0));
    const int height = own ? d.grid->height() : static_cast<int>(rng.uniform(40.0, 90.0));
    auto centre = [&](int ix, int iy) {
      return origin.transform_point(Vec2((ix + 0.5) * cell, (iy + 0.5) * cell));
    };
    std::vector<double> radii = {0.0, rng.uniform(0.0, 0.1), rng.uniform(0.1, 0.4)};
    for (int k = 0; k < 2; ++k) {  // ties: a radius equal to some centre's clearance
      const double c = w.clearance(centre(static_cast<int>(rng.uniform(0.0, width - 1.0)),
                                          static_cast<int>(rng.uniform(0.0, height - 1.0))));
      if (c >= 0.0 && std::isfinite(c)) radii.push_back(c);
    }
    for (const double r : radii) {
      const FreeRaster f = free_cells(w, r, origin, cell, width, height);
      ASSERT_EQ(f.free.size(), static_cast<std::size_t>(width * height));
      for (int iy = 0; iy < height; ++iy)
        for (int ix = 0; ix < width; ++ix) {
          const bool expect = w.clearance_brute_force(centre(ix, iy)) > r;
          ASSERT_EQ(f.is_free(ix, iy), expect)
              << "trial " << trial << " r " << r << " cell " << ix << ", " << iy;
          free_cells_seen += expect;
          ++cells;
        }
    }
  }
  // Both kinds of cell occur in numbers.
  EXPECT_GT(free_cells_seen, cells / 5);
  EXPECT_LT(free_cells_seen, cells * 9 / 10);
}

}  // namespace
}  // namespace floornav
