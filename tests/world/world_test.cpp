// The indexed obstacle world against its brute-force oracle, bounds, insides, big overlaps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <vector>

#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"
#include "support/bits.hpp"

using namespace floornav;

namespace {
WorldDesc sample_world(std::uint64_t seed, int polygons, int circles) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  WorldDesc d;
  d.bounds = Box2{Vec2(-5, -4), Vec2(5, 4)};
  for (int i = 0; i < polygons; ++i)
    d.polygons.push_back(make_rectangle(Vec2(-4 + 8 * u(rng), -3 + 6 * u(rng)),
                                        Vec2(0.1 + 0.8 * u(rng), 0.1 + 0.8 * u(rng)),
                                        6.0 * u(rng)));
  for (int i = 0; i < circles; ++i)
    d.circles.push_back({Vec2(-4 + 8 * u(rng), -3 + 6 * u(rng)), 0.05 + 0.3 * u(rng)});
  return d;
}
}  // namespace

// The spatial index must give exactly what testing every edge gives.
TEST(World, IndexedQueriesMatchBruteForce) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const World w(sample_world(seed, 40, 15));
    std::mt19937_64 rng(seed + 100);
    std::uniform_real_distribution<double> x(-6.0, 6.0), y(-5.0, 5.0), a(-kPi, kPi);
    for (int i = 0; i < 2000; ++i) {
      const Vec2 p(x(rng), y(rng));
      const double th = a(rng);
      const Vec2 dir(std::cos(th), std::sin(th));
      ASSERT_DOUBLE_EQ(w.cast_ray(p, dir, 20.0), w.cast_ray_brute_force(p, dir, 20.0))
          << "seed " << seed << " at " << p.transpose() << " dir " << th;
      ASSERT_DOUBLE_EQ(w.clearance(p), w.clearance_brute_force(p)) << p.transpose();
    }
  }
}

// Rays from free points among concave polygons of either winding, against every edge tested:
// the casts skip the edges seen from their solid side and must lose no hit by it.
TEST(World, CastsFromFreePointsMatchBruteForceAmongPolygonsOfEitherWinding) {
  std::mt19937_64 rng(44);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int free_origins = 0;
  for (int world_no = 0; world_no < 20; ++world_no) {
    WorldDesc d;
    d.bounds = Box2{Vec2(0, 0), Vec2(8, 8)};
    for (int p = 0; p < 25; ++p) {
      const Vec2 c(8 * u(rng), 8 * u(rng));
      const int n = 3 + static_cast<int>(6 * u(rng));
      std::vector<Vec2> poly;
      for (int i = 0; i < n; ++i) {  // star-shaped, concave where a radius dips
        const double a = 2.0 * kPi * (i + 0.3 * (u(rng) - 0.5)) / n;
        const double r = 0.2 + 0.8 * u(rng);
        poly.emplace_back(c.x() + r * std::cos(a), c.y() + r * std::sin(a));
      }
      if (u(rng) < 0.5) std::reverse(poly.begin(), poly.end());
      d.polygons.push_back(poly);
    }
    const World w(d);
    for (int i = 0; i < 300; ++i) {
      const Vec2 p(8 * u(rng), 8 * u(rng));
      if (w.is_inside_obstacle(p)) continue;
      ++free_origins;
      const double th = 2.0 * kPi * u(rng);
      const Vec2 dir(std::cos(th), std::sin(th));
      ASSERT_DOUBLE_EQ(w.cast_ray(p, dir, 20.0), w.cast_ray_brute_force(p, dir, 20.0))
          << "world " << world_no << " at " << p.transpose() << " dir " << th;
      // Straight at a vertex: the ray enters there, or grazes it within rounding. Each edge
      // reaches kSegmentEndSlack past its ends, so one of the vertex's edges seen from the free
      // side catches the ray wherever the other is skipped.
      const Vec2 v = d.polygons[static_cast<std::size_t>(25 * u(rng)) % 25][0];
      const Vec2 at = (v - p).normalized();
      ASSERT_NEAR(w.cast_ray(p, at, 20.0), w.cast_ray_brute_force(p, at, 20.0), 1e-9)
          << "world " << world_no << " at " << p.transpose() << " towards " << v.transpose();
    }
  }
  EXPECT_GT(free_origins, 2000);
}

// The mechanism: from inside a square (of either winding), every edge is seen from its solid
// side, so a cast that takes its origin to be free tests none of them and sees nothing.
TEST(World, EdgesSeenFromTheirSolidSideAreNotTested) {
  for (const bool clockwise : {false, true}) {
    std::vector<Vec2> square{{1, 1}, {3, 1}, {3, 3}, {1, 3}};
    if (clockwise) std::reverse(square.begin(), square.end());
    WorldDesc d;
    d.polygons.push_back(square);
    const World w(d);
    const Vec2 inside(2.0, 2.5), outside(0.0, 2.5), east(1.0, 0.0);
    EXPECT_EQ(w.cast_ray(inside, east, 5.0), 0.0);  // cast_ray knows the origin is solid
    EXPECT_EQ(w.cast_ray_from_free(inside, east, 5.0), 5.0) << "clockwise " << clockwise;
    std::vector<double> out(4, -1.0);
    const std::vector<Vec2> dirs{{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    const std::vector<double> angles{0.0, 0.5 * kPi, kPi, -0.5 * kPi};
    FanScratch scratch;
    w.cast_fan_from_free(inside, dirs, angles, 5.0, out, scratch);
    for (const double r : out) EXPECT_EQ(r, 5.0) << "clockwise " << clockwise;
    // From outside, the near edge faces the origin and the far one is skipped: 1 m to x = 1.
    EXPECT_EQ(w.cast_ray_from_free(outside, east, 5.0), 1.0);
  }
}

TEST(World, BoundsAreWallsAndOutsideIsSolid) {
  WorldDesc d;
  d.bounds = Box2{Vec2(0, 0), Vec2(4, 2)};
  const World w(d);
  EXPECT_DOUBLE_EQ(w.clearance(Vec2(1, 0.5)), 0.5);
  EXPECT_DOUBLE_EQ(w.cast_ray(Vec2(1, 1), Vec2(1, 0), 10.0), 3.0);
  EXPECT_DOUBLE_EQ(w.cast_ray(Vec2(1, 1), Vec2(1, 0), 2.0), 2.0);  // out of range
  EXPECT_LT(w.clearance(Vec2(5, 1)), 0.0);
  EXPECT_TRUE(w.is_inside_obstacle(Vec2(-1, 1)));
  EXPECT_FALSE(w.is_inside_obstacle(Vec2(2, 1)));
}

TEST(World, InsideAPolygonIsNegative) {
  WorldDesc d;
  d.polygons.push_back({{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  const World w(d);
  EXPECT_DOUBLE_EQ(w.clearance(Vec2(1, 0.5)), -0.5);
  EXPECT_DOUBLE_EQ(w.clearance(Vec2(3, 1)), 1.0);
  EXPECT_DOUBLE_EQ(w.cast_ray(Vec2(1, 1), Vec2(1, 0), 5.0), 0.0);
  EXPECT_DOUBLE_EQ(w.cast_ray(Vec2(-1, 1), Vec2(1, 0), 5.0), 1.0);
}

TEST(World, EmptyWorldSeesNothing) {
  const World w(WorldDesc{});
  EXPECT_DOUBLE_EQ(w.cast_ray(Vec2(0, 0), Vec2(1, 0), 3.0), 3.0);
  EXPECT_TRUE(std::isinf(w.clearance(Vec2(0, 0))));
}

// Many large overlapping obstacles coarsen the index instead of filling it with billions of
// entries (a hang found by the reliability work); queries stay exact.
TEST(World, ManyLargeOverlappingObstaclesStayExact) {
  WorldDesc d;
  d.bounds = Box2{Vec2(0, 0), Vec2(1000, 1000)};
  for (int i = 0; i < 20000; ++i) d.circles.push_back({Vec2(500 + i % 7, 500), 400.0});
  const World w(d);
  for (const Vec2& p : {Vec2(1, 1), Vec2(50, 900), Vec2(500, 500), Vec2(999, 2)}) {
    EXPECT_DOUBLE_EQ(w.clearance(p), w.clearance_brute_force(p));
    EXPECT_DOUBLE_EQ(w.cast_ray(p, Vec2(1, 0), 2000.0),
                     w.cast_ray_brute_force(p, Vec2(1, 0), 2000.0));
  }
}

namespace {
// Walks `steps` steps of random length up to `stride` (every 50th a jump of up to 2 m) from
// `start`, querying with and without the hint: they must agree bit for bit. Returns how many
// queries searched the index (the hint's point moved).
int walk_with_hint(const World& w, Vec2 p, int steps, double stride, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), a(-kPi, kPi);
  ClearanceHint hint;
  int searches = 0;
  for (int i = 0; i < steps; ++i) {
    const double len = (i % 50 == 49 ? 2.0 : stride) * u(rng), th = a(rng);
    const Vec2 step = len * Vec2(std::cos(th), std::sin(th));
    p += w.extent().contains(p + step) ? step : -step;  // stays about the world
    const Vec2 before = hint.at;
    const double hinted = w.clearance(p, hint);
    EXPECT_EQ(test::bits(hinted), test::bits(w.clearance(p)))
        << "step " << i << " at " << p.transpose();
    searches += i == 0 || hint.at != before;
  }
  return searches;
}
}  // namespace

// A hint answers most queries of a short-stepping walker alone, and always with the full
// search's bits: through obstacles (negative), outside the bounds, past circles.
TEST(World, ClearanceHintGivesTheSearchBitsAndSkipsMostSearches) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    // Dense: the walk spends much of its time inside obstacles, where every query searches.
    const World dense(sample_world(seed, 40, 15));
    EXPECT_GT(walk_with_hint(dense, Vec2(0.0, 0.0), 4000, 0.01, seed), 4000 / 50)
        << "seed " << seed << ": jumps and contacts must search";
    const World sparse(sample_world(seed, 8, 4));
    const int searches = walk_with_hint(sparse, Vec2(0.0, 0.0), 4000, 0.01, seed);
    EXPECT_LT(searches, 4000 / 4) << "seed " << seed << ": the hint was hardly used";
    EXPECT_GT(searches, 4000 / 100) << "seed " << seed << ": jumps must search";
  }
}

// Stepping into a polygon: the step that ends inside is negative, exactly as without the hint
// (the hint proves a point outside only while nothing could have been crossed).
TEST(World, ClearanceHintSeesTheStepIntoAnObstacle) {
  WorldDesc d;
  d.polygons.push_back({{0, 0}, {2, 0}, {2, 2}, {0, 2}});
  d.circles.push_back({Vec2(5, 1), 0.5});
  const World w(d);
  ClearanceHint hint;
  double last = 0.0;
  for (double x = -1.0; x < 1.0; x += 0.0137) {
    last = w.clearance(Vec2(x, 1.0), hint);
    EXPECT_EQ(last, w.clearance(Vec2(x, 1.0))) << x;
  }
  EXPECT_LT(last, 0.0);
  for (double x = 2.5; x < 6.0; x += 0.0137)  // into the circle
    EXPECT_EQ(w.clearance(Vec2(x, 1.0), hint), w.clearance(Vec2(x, 1.0))) << x;
}

// An occupancy grid is searched in full every time: the hint is left unused.
TEST(World, ClearanceHintIsUnusedWithAGrid) {
  std::vector<std::uint8_t> cells(20 * 20, 0);
  cells[5 * 20 + 5] = 1;
  auto grid = std::make_shared<const OccupancyGrid>(20, 20, 0.1, Pose2{}, std::move(cells));
  WorldDesc d;
  d.grid = grid;
  d.polygons.push_back({{1.5, 1.5}, {1.8, 1.5}, {1.8, 1.8}});
  const World w(d);
  ClearanceHint hint;
  for (double x = 0.0; x < 1.5; x += 0.01) {
    EXPECT_EQ(w.clearance(Vec2(x, 0.3), hint), w.clearance(Vec2(x, 0.3))) << x;
    EXPECT_FALSE(hint.valid);
  }
}

// A map without bounds is the whole world: off the map is solid, its edge a wall (it once counted
// as free floor, and a robot drove round a full-height wall by leaving the map). With bounds, the
// bounds decide as before.
TEST(World, OffAMapWithoutBoundsIsSolid) {
  // 10 x 4 cells of 0.5 m, free but for a full-height wall in column 5; origin (1, 2), turned.
  for (const double yaw : {0.0, 0.3}) {
    SCOPED_TRACE(yaw);
    std::vector<std::uint8_t> occ(40, 0);
    for (int y = 0; y < 4; ++y) occ[static_cast<std::size_t>(y * 10 + 5)] = 1;
    const Pose2 origin{{1.0, 2.0}, yaw};
    WorldDesc d;
    d.grid = std::make_shared<const OccupancyGrid>(10, 4, 0.5, origin, std::move(occ));
    const World w(d);
    const auto at = [&](double gx, double gy) { return origin.transform_point({gx, gy}); };
    EXPECT_FALSE(w.is_inside_obstacle(at(1.0, 1.0)));   // on the map, free
    EXPECT_NEAR(w.clearance(at(1.0, 1.0)), 1.0, 1e-9);  // the map's lower and upper edges
    for (const Vec2& off : {at(2.75, -0.5), at(2.75, 2.5), at(-0.5, 1.0), at(5.5, 3.0)}) {
      EXPECT_TRUE(w.is_inside_obstacle(off));
      EXPECT_LT(w.clearance(off), 0.0);
      EXPECT_LT(w.clearance_brute_force(off), 0.0);
    }
    // A ray from the map towards the outside stops at the edge.
    const Vec2 down = Vec2(std::sin(yaw), -std::cos(yaw));
    EXPECT_NEAR(w.cast_ray(at(1.0, 1.0), down, 10.0), 1.0, 1e-9);
    EXPECT_NEAR(w.cast_ray_brute_force(at(1.0, 1.0), down, 10.0), 1.0, 1e-9);
    // Nothing off the map is reachable on the free-cell raster either.
    EXPECT_TRUE(w.map_edge().size() == 4);
    EXPECT_FALSE(w.bounds().has_value());  // the scenario's bounds stay as given
  }
  // With bounds the map's edge is no wall: the bounds are.
  WorldDesc d;
  d.grid = std::make_shared<const OccupancyGrid>(2, 2, 1.0, Pose2{}, std::vector<std::uint8_t>(4));
  d.bounds = Box2{{-5.0, -5.0}, {5.0, 5.0}};
  const World w(d);
  EXPECT_TRUE(w.map_edge().empty());
  EXPECT_FALSE(w.is_inside_obstacle({3.0, 3.0}));
}
