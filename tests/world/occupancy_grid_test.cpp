#include "floornav/world/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace floornav {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// A width x height grid with the listed cells occupied.
OccupancyGrid make_grid(int width, int height, double resolution, Pose2 origin,
                        std::initializer_list<std::array<int, 2>> cells) {
  std::vector<std::uint8_t> occ(static_cast<std::size_t>(width) * height, 0);
  for (const auto& c : cells) occ[static_cast<std::size_t>(c[1]) * width + c[0]] = 1;
  return OccupancyGrid(width, height, resolution, origin, std::move(occ));
}

// --- hand-worked values -----------------------------------------------------------------------

TEST(OccupancyGrid, RayAlongARowHitsTheCellsNearEdge) {
  // 0.1 m cells, origin at (1, 2). Cell (7, 2) spans x in [1.7, 1.8] in the world.
  const OccupancyGrid g = make_grid(10, 5, 0.1, Pose2{{1.0, 2.0}, 0.0}, {{7, 2}});
  // From the centre of cell (1, 2) = world (1.15, 2.25): 1.7 - 1.15 = 0.55.
  EXPECT_NEAR(g.cast_ray({1.15, 2.25}, {1.0, 0.0}, 5.0), 0.55, 1e-12);
  // Backwards along the row there is nothing: max_range.
  EXPECT_EQ(g.cast_ray({1.15, 2.25}, {-1.0, 0.0}, 5.0), 5.0);
  // Range shorter than the hit.
  EXPECT_EQ(g.cast_ray({1.15, 2.25}, {1.0, 0.0}, 0.5), 0.5);
  // From the far side, leftwards: the ray meets the cell's right edge x = 1.8.
  EXPECT_NEAR(g.cast_ray({1.95, 2.25}, {-1.0, 0.0}, 5.0), 0.15, 1e-12);
}

TEST(OccupancyGrid, DiagonalRay) {
  // Unit cells, occupied (3, 4). The ray y = x + 0.5 from (0.5, 1) crosses y = 4 at x = 3.5,
  // entering cell (3, 4) at distance |(3, 3)| = 3 sqrt(2).
  const OccupancyGrid g = make_grid(6, 6, 1.0, Pose2{}, {{3, 4}});
  const Vec2 dir = Vec2(1.0, 1.0).normalized();
  EXPECT_NEAR(g.cast_ray({0.5, 1.0}, dir, 100.0), 3.0 * std::sqrt(2.0), 1e-12);
}

TEST(OccupancyGrid, DiagonalRayThroughACornerHitsTheCellTouchingIt) {
  // The ray from (0.5, 0.5) along (1, 1) passes the corner (2, 2) of cell (2, 1) at 1.5 sqrt 2.
  const OccupancyGrid g = make_grid(5, 5, 1.0, Pose2{}, {{2, 1}});
  const Vec2 dir = Vec2(1.0, 1.0).normalized();
  EXPECT_NEAR(g.cast_ray({0.5, 0.5}, dir, 100.0), 1.5 * std::sqrt(2.0), 1e-12);
}

TEST(OccupancyGrid, RayStartingInsideAnOccupiedCellIsZero) {
  const OccupancyGrid g = make_grid(4, 4, 0.5, Pose2{}, {{1, 1}});
  EXPECT_EQ(g.cast_ray({0.6, 0.7}, {0.0, 1.0}, 3.0), 0.0);
}

TEST(OccupancyGrid, RayFromOutsideIsClippedToTheGrid) {
  // Grid [0, 2] x [0, 2] with 0.5 m cells; cell (0, 1) spans y in [0.5, 1.0].
  const OccupancyGrid g = make_grid(4, 4, 0.5, Pose2{}, {{0, 1}});
  EXPECT_NEAR(g.cast_ray({-3.0, 0.75}, {1.0, 0.0}, 10.0), 3.0, 1e-12);
  EXPECT_EQ(g.cast_ray({-3.0, 0.75}, {1.0, 0.0}, 2.5), 2.5);
  EXPECT_EQ(g.cast_ray({-3.0, 0.75}, {-1.0, 0.0}, 10.0), 10.0);  // pointing away
  EXPECT_EQ(g.cast_ray({-3.0, 5.0}, {1.0, 0.0}, 10.0), 10.0);    // passes above
  EXPECT_EQ(g.cast_ray({-3.0, 0.75}, {1.0, 0.0}, kInf), 3.0);
  EXPECT_EQ(g.cast_ray({1.75, 0.25}, {0.0, 1.0}, kInf), kInf);  // leaves the grid
}

TEST(OccupancyGrid, RotatedOrigin) {
  // Origin at (5, 1) with yaw 90 deg: grid +x is world +y, grid +y is world -x, so grid point
  // (gx, gy) is world (5 - gy, 1 + gx). Cell (3, 1) with 0.5 m cells spans gx in [1.5, 2].
  const OccupancyGrid g = make_grid(4, 3, 0.5, Pose2{{5.0, 1.0}, kPi / 2}, {{3, 1}});
  // Grid point (0.25, 0.75) = world (4.25, 1.25); world +y is grid +x; hit at gx = 1.5.
  EXPECT_NEAR(g.cast_ray({4.25, 1.25}, {0.0, 1.0}, 10.0), 1.25, 1e-12);
  // Clearance of the same point: gap 1.25 along grid x, 0 along grid y.
  EXPECT_NEAR(g.clearance({4.25, 1.25}), 1.25, 1e-12);
  Vec2 lo, hi;
  g.world_extent(&lo, &hi);  // gx in [0, 2], gy in [0, 1.5]
  EXPECT_NEAR(lo.x(), 3.5, 1e-12);
  EXPECT_NEAR(lo.y(), 1.0, 1e-12);
  EXPECT_NEAR(hi.x(), 5.0, 1e-12);
  EXPECT_NEAR(hi.y(), 3.0, 1e-12);
}

TEST(OccupancyGrid, ClearanceDiagonallyOffACorner) {
  // Cell (2, 2) with 0.5 m cells is the square [1, 1.5]^2. From (0.7, 0.6) the nearest point is
  // its corner (1, 1): sqrt(0.3^2 + 0.4^2) = 0.5.
  const OccupancyGrid g = make_grid(4, 4, 0.5, Pose2{}, {{2, 2}});
  EXPECT_NEAR(g.clearance({0.7, 0.6}), 0.5, 1e-12);
  Vec2 q;
  ASSERT_TRUE(g.nearest_occupied_point({0.7, 0.6}, &q));
  EXPECT_NEAR(q.x(), 1.0, 1e-12);
  EXPECT_NEAR(q.y(), 1.0, 1e-12);
  // Straight left of the square's edge: 1 - 0.2 = 0.8.
  EXPECT_NEAR(g.clearance({0.2, 1.2}), 0.8, 1e-12);
  // Outside the grid ([0, 2]^2): to the corner (1, 1) from (-2, -2) is 3 sqrt 2, and from
  // (-3, 1.25) straight to the edge x = 1 is 4 (exact, not "clamp and add").
  EXPECT_NEAR(g.clearance({-2.0, -2.0}), 3.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(g.clearance({-3.0, 1.25}), 4.0, 1e-12);
  // Inside: minus the distance to the cell's own border, 1.1 - 1.0.
  EXPECT_NEAR(g.clearance({1.1, 1.25}), -0.1, 1e-12);
  ASSERT_TRUE(g.nearest_occupied_point({1.1, 1.25}, &q));
  EXPECT_NEAR(q.x(), 1.0, 1e-12);
  EXPECT_NEAR(q.y(), 1.25, 1e-12);
}

TEST(OccupancyGrid, EmptyGrid) {
  const OccupancyGrid g = make_grid(3, 2, 1.0, Pose2{}, {});
  EXPECT_EQ(g.occupied_count(), 0u);
  EXPECT_EQ(g.clearance({1.0, 1.0}), kInf);
  EXPECT_EQ(g.cast_ray({0.5, 0.5}, {1.0, 0.0}, 7.0), 7.0);
  Vec2 q;
  EXPECT_FALSE(g.nearest_occupied_point({1.0, 1.0}, &q));
  EXPECT_EQ(g.nearest_occupied_index(0, 0), -1);
}

TEST(OccupancyGrid, Accessors) {
  const OccupancyGrid g = make_grid(3, 2, 0.25, Pose2{{1.0, 2.0}, 0.0}, {{2, 1}, {0, 0}});
  EXPECT_EQ(g.width(), 3);
  EXPECT_EQ(g.height(), 2);
  EXPECT_EQ(g.resolution(), 0.25);
  EXPECT_EQ(g.occupied_count(), 2u);
  EXPECT_TRUE(g.occupied(2, 1));
  EXPECT_TRUE(g.occupied(0, 0));
  EXPECT_FALSE(g.occupied(1, 0));
  EXPECT_FALSE(g.occupied(-1, 0));  // outside counts as free
  EXPECT_FALSE(g.occupied(3, 1));
  EXPECT_EQ(g.nearest_occupied_index(2, 0), 1 * 3 + 2);
  EXPECT_EQ(g.nearest_occupied_index(0, 1), 0);
}

TEST(OccupancyGrid, RejectsBadConstruction) {
  EXPECT_THROW(OccupancyGrid(0, 2, 1.0, Pose2{}, {}), std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(2, -1, 1.0, Pose2{}, {}), std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(2, 2, 0.0, Pose2{}, std::vector<std::uint8_t>(4)),
               std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(2, 2, std::nan(""), Pose2{}, std::vector<std::uint8_t>(4)),
               std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(2, 2, kInf, Pose2{}, std::vector<std::uint8_t>(4)),
               std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(2, 2, 1.0, Pose2{}, std::vector<std::uint8_t>(3)),
               std::invalid_argument);
  EXPECT_THROW(
      OccupancyGrid(2, 2, 1.0, Pose2{{std::nan(""), 0.0}, 0.0}, std::vector<std::uint8_t>(4)),
      std::invalid_argument);
}

// --- brute-force oracle -----------------------------------------------------------------------

/// The world-frame corners (counter-clockwise) of cell (ix, iy).
std::array<Vec2, 4> cell_corners(const OccupancyGrid& g, int ix, int iy) {
  const double r = g.resolution();
  return {g.origin().transform_point({ix * r, iy * r}),
          g.origin().transform_point({(ix + 1) * r, iy * r}),
          g.origin().transform_point({(ix + 1) * r, (iy + 1) * r}),
          g.origin().transform_point({ix * r, (iy + 1) * r})};
}

/// Entry distance of the ray into the closed convex quad (Cyrus-Beck), or +inf.
double ray_quad(const std::array<Vec2, 4>& q, const Vec2& o, const Vec2& d) {
  double t0 = 0.0;
  double t1 = kInf;
  for (int i = 0; i < 4; ++i) {
    const Vec2 a = q[i];
    const Vec2 b = q[(i + 1) % 4];
    const Vec2 n(b.y() - a.y(), a.x() - b.x());  // outward normal (counter-clockwise quad)
    const double num = n.dot(a - o);             // inside when >= 0 at t = 0
    const double den = n.dot(d);
    if (den == 0.0) {
      if (num < 0.0) return kInf;
      continue;
    }
    const double t = num / den;
    if (den < 0.0) {
      t0 = std::max(t0, t);
    } else {
      t1 = std::min(t1, t);
    }
  }
  return t0 <= t1 ? t0 : kInf;
}

double point_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + s * ab)).norm();
}

/// Signed distance to the union of occupied squares, as `clearance` defines it.
double brute_clearance(const OccupancyGrid& g, const Vec2& p) {
  double best = kInf;
  for (int iy = 0; iy < g.height(); ++iy) {
    for (int ix = 0; ix < g.width(); ++ix) {
      if (!g.occupied(ix, iy)) continue;
      const auto q = cell_corners(g, ix, iy);
      double d = kInf;
      for (int i = 0; i < 4; ++i) d = std::min(d, point_segment(p, q[i], q[(i + 1) % 4]));
      if (ray_quad(q, p, Vec2(1.0, 0.0)) == 0.0) return -d;  // p inside this square
      best = std::min(best, d);
    }
  }
  return best;
}

double brute_ray(const OccupancyGrid& g, const Vec2& o, const Vec2& d, double max_range) {
  double best = max_range;
  for (int iy = 0; iy < g.height(); ++iy) {
    for (int ix = 0; ix < g.width(); ++ix) {
      if (g.occupied(ix, iy)) best = std::min(best, ray_quad(cell_corners(g, ix, iy), o, d));
    }
  }
  return best;
}

struct RandomGrid {
  explicit RandomGrid(std::mt19937_64& rng) {
    std::uniform_int_distribution<int> size(1, 24);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    width = size(rng);
    height = size(rng);
    const double density = unit(rng) < 0.3 ? 0.02 : 0.4 * unit(rng);
    occ.resize(static_cast<std::size_t>(width) * height);
    for (auto& c : occ) c = unit(rng) < density ? 1 : 0;
    if (unit(rng) < 0.5) occ[rng() % occ.size()] = 1;
    resolution = 0.05 + unit(rng);
    origin = Pose2{{4.0 * unit(rng) - 2.0, 4.0 * unit(rng) - 2.0},
                   unit(rng) < 0.3 ? 0.0 : (2.0 * unit(rng) - 1.0) * kPi};
  }
  int width;
  int height;
  double resolution;
  Pose2 origin;
  std::vector<std::uint8_t> occ;
};

TEST(OccupancyGrid, MatchesBruteForceOracle) {
  std::mt19937_64 rng(20261123);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int queries = 0;
  int hits = 0;
  int negatives = 0;
  for (int grid_no = 0; grid_no < 50; ++grid_no) {
    const RandomGrid r(rng);
    const OccupancyGrid g(r.width, r.height, r.resolution, r.origin, r.occ);
    // Feature transform: the nearest centre, by distance (ties may pick either cell).
    for (int iy = 0; iy < g.height(); ++iy) {
      for (int ix = 0; ix < g.width(); ++ix) {
        long best = -1;
        for (int oy = 0; oy < g.height(); ++oy) {
          for (int ox = 0; ox < g.width(); ++ox) {
            const long d2 = long(ox - ix) * (ox - ix) + long(oy - iy) * (oy - iy);
            if (g.occupied(ox, oy) && (best < 0 || d2 < best)) best = d2;
          }
        }
        const std::int32_t n = g.nearest_occupied_index(ix, iy);
        if (best < 0) {
          ASSERT_EQ(n, -1);
          continue;
        }
        ASSERT_GE(n, 0);
        const int nx = n % g.width();
        const int ny = n / g.width();
        ASSERT_TRUE(g.occupied(nx, ny));
        ASSERT_EQ(long(nx - ix) * (nx - ix) + long(ny - iy) * (ny - iy), best);
      }
    }
    Vec2 lo, hi;
    g.world_extent(&lo, &hi);
    const Vec2 span = hi - lo;
    for (int k = 0; k < 20; ++k, ++queries) {
      // Points over the grid and up to half its size beyond every side.
      const Vec2 p(lo.x() + span.x() * (2.0 * unit(rng) - 0.5),
                   lo.y() + span.y() * (2.0 * unit(rng) - 0.5));
      const double a = 2.0 * kPi * unit(rng);
      const Vec2 dir(std::cos(a), std::sin(a));
      const double max_range = unit(rng) < 0.2 ? kInf : 3.0 * span.norm() * unit(rng);
      const double expected_ray = brute_ray(g, p, dir, max_range);
      const double ray = g.cast_ray(p, dir, max_range);
      if (expected_ray == kInf) {
        ASSERT_EQ(ray, kInf) << "grid " << grid_no << " query " << k;
      } else {
        ASSERT_NEAR(ray, expected_ray, 1e-9) << "grid " << grid_no << " query " << k;
      }
      if (expected_ray < max_range) ++hits;
      const double expected = brute_clearance(g, p);
      if (expected < 0.0) ++negatives;
      if (expected == kInf) {
        ASSERT_EQ(g.clearance(p), kInf);
      } else {
        ASSERT_NEAR(g.clearance(p), expected, 1e-9) << "grid " << grid_no << " query " << k;
        Vec2 q;
        ASSERT_TRUE(g.nearest_occupied_point(p, &q));
        ASSERT_NEAR((q - p).norm(), std::abs(expected), 1e-9);
      }
    }
  }
  EXPECT_EQ(queries, 1000);
  EXPECT_GT(hits, 150);  // the sweep exercises hits, not only misses
  EXPECT_GT(negatives, 10);
}

TEST(OccupancyGrid, SparseGridsMatchOracle) {
  // Few far-apart cells: where nearest-centre ties and the square metric differ most.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int grid_no = 0; grid_no < 40; ++grid_no) {
    const int w = 20 + static_cast<int>(rng() % 60);
    const int h = 20 + static_cast<int>(rng() % 60);
    std::vector<std::uint8_t> occ(static_cast<std::size_t>(w) * h, 0);
    const int n = 1 + static_cast<int>(rng() % 5);
    for (int i = 0; i < n; ++i) occ[rng() % occ.size()] = 1;
    const OccupancyGrid g(w, h, 1.0, Pose2{}, occ);
    for (int k = 0; k < 200; ++k) {
      const Vec2 p(w * unit(rng), h * unit(rng));
      ASSERT_NEAR(g.clearance(p), brute_clearance(g, p), 1e-9);
    }
  }
}

}  // namespace
}  // namespace floornav
