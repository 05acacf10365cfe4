// Raster line of sight and string pulling, on hand-worked cases.
#include "floornav/planning/string_pulling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "floornav/planning/line_of_sight.hpp"
#include "floornav/planning/octile_astar.hpp"
#include "planning/planning_test_support.hpp"

namespace floornav {
namespace {

using test::raster;

const double kSqrt2 = std::sqrt(2.0);

TEST(LineOfSight, ThroughACornerNeedsBothNeighbours) {
  EXPECT_TRUE(line_of_sight(raster(2, 2, {}), {0.5, 0.5}, {1.5, 1.5}));
  EXPECT_FALSE(line_of_sight(raster(2, 2, {{1, 0}}), {0.5, 0.5}, {1.5, 1.5}));
  EXPECT_FALSE(line_of_sight(raster(2, 2, {{0, 1}}), {0.5, 0.5}, {1.5, 1.5}));
}

TEST(LineOfSight, AlongABorderNeedsBothSides) {
  // The segment y = 1 runs between rows 0 and 1.
  EXPECT_TRUE(line_of_sight(raster(4, 2, {}), {0.5, 1.0}, {3.5, 1.0}));
  EXPECT_FALSE(line_of_sight(raster(4, 2, {{2, 0}}), {0.5, 1.0}, {3.5, 1.0}));
  EXPECT_FALSE(line_of_sight(raster(4, 2, {{2, 1}}), {0.5, 1.0}, {3.5, 1.0}));
  // A row inside: only that row counts.
  EXPECT_TRUE(line_of_sight(raster(4, 2, {{2, 1}}), {0.5, 0.5}, {3.5, 0.5}));
}

TEST(LineOfSight, ShallowSegmentSeesEveryCellItCrosses) {
  // (0.5, 0.5) to (4.5, 1.5) crosses from row 0 to row 1 at x = 2.5, inside column 2.
  const Vec2 a(0.5, 0.5), b(4.5, 1.5);
  EXPECT_TRUE(line_of_sight(raster(5, 2, {{0, 1}, {4, 0}}), a, b));
  EXPECT_FALSE(line_of_sight(raster(5, 2, {{2, 0}}), a, b));
  EXPECT_FALSE(line_of_sight(raster(5, 2, {{2, 1}}), a, b));
  EXPECT_FALSE(line_of_sight(raster(5, 2, {{3, 1}}), a, b));
  EXPECT_FALSE(line_of_sight(raster(5, 2, {{1, 0}}), a, b));
}

TEST(PullString, ShortensTheOctilePathToTheStraightLine) {
  const FreeRaster r = raster(10, 10, {});
  const auto p = octile_astar(r, {0, 0}, {8, 3});
  ASSERT_TRUE(p);
  std::vector<Vec2> pts;
  for (const auto& c : p->cells) pts.emplace_back(c.x + 0.5, c.y + 0.5);
  const auto pulled = pull_string(r, pts);
  ASSERT_EQ(pulled.size(), 2u);
  EXPECT_NEAR((pulled[1] - pulled[0]).norm(), std::sqrt(73.0), 1e-12);
  EXPECT_NEAR(p->length, 5.0 + 3.0 * kSqrt2, 1e-12);  // 8.2 % longer than sqrt(73) = 8.54
}

TEST(PullString, KeepsTheCornerOfAWall) {
  const FreeRaster r = raster(5, 5, {{2, 0}, {2, 1}, {2, 2}, {2, 3}});
  const auto p = octile_astar(r, {0, 0}, {4, 0});
  ASSERT_TRUE(p);
  std::vector<Vec2> pts;
  for (const auto& c : p->cells) pts.emplace_back(c.x + 0.5, c.y + 0.5);
  const auto pulled = pull_string(r, pts);
  double len = 0.0;
  for (std::size_t i = 1; i < pulled.size(); ++i) {
    EXPECT_TRUE(line_of_sight(r, pulled[i - 1], pulled[i]));
    len += (pulled[i] - pulled[i - 1]).norm();
  }
  // Over (1.5, 4.5) and (3.5, 4.5): 2 * sqrt(1 + 16) + 2.
  EXPECT_NEAR(len, 2.0 * std::sqrt(17.0) + 2.0, 1e-12);
  EXPECT_LT(len, p->length);
}

// Greedy string pulling with any line-of-sight test: the pulled path keeps exactly the vertices
// the test cannot see past.
TEST(PullString, WithAnyLineOfSightTest) {
  const std::vector<Vec2> pts{{0, 0}, {1, 0}, {2, 0}, {2, 1}, {2, 2}};
  std::vector<Vec2> out;
  pull_string(
      pts, [](const Vec2&, const Vec2&) { return true; }, out);
  EXPECT_EQ(out, (std::vector<Vec2>{{0, 0}, {2, 2}}));
  pull_string(
      pts, [](const Vec2&, const Vec2&) { return false; }, out);
  EXPECT_EQ(out, pts);
  // Sight only along an axis: the corner (2, 0) stays, the points on the legs go.
  pull_string(
      pts, [](const Vec2& a, const Vec2& b) { return a.x() == b.x() || a.y() == b.y(); }, out);
  EXPECT_EQ(out, (std::vector<Vec2>{{0, 0}, {2, 0}, {2, 2}}));
}

}  // namespace
}  // namespace floornav
