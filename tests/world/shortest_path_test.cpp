// Octile A*, raster line of sight, string pulling and the scenario optimum, on hand-worked cases.
#include "floornav/world/shortest_path.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <numbers>
#include <vector>

#include "floornav/io/movingai_map.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

const double kSqrt2 = std::sqrt(2.0);

/// A width x height raster, all free but the listed cells.
FreeRaster raster(int width, int height, std::initializer_list<std::array<int, 2>> blocked) {
  FreeRaster r;
  r.width = width;
  r.height = height;
  r.free.assign(static_cast<std::size_t>(width) * height, 1);
  for (const auto& c : blocked) r.free[static_cast<std::size_t>(c[1]) * width + c[0]] = 0;
  return r;
}

/// Each step of a path goes to one of the 8 neighbours, through free cells, cutting no corner.
void expect_valid_path(const FreeRaster& r, const GridPath& p) {
  double length = 0.0;
  for (std::size_t i = 1; i < p.cells.size(); ++i) {
    const GridCell a = p.cells[i - 1], b = p.cells[i];
    const int dx = b.x - a.x, dy = b.y - a.y;
    ASSERT_TRUE(std::abs(dx) <= 1 && std::abs(dy) <= 1 && (dx != 0 || dy != 0));
    ASSERT_TRUE(r.is_free(b.x, b.y));
    if (dx != 0 && dy != 0) {
      ASSERT_TRUE(r.is_free(a.x + dx, a.y) && r.is_free(a.x, a.y + dy)) << "corner cut";
      length += kSqrt2;
    } else {
      length += 1.0;
    }
  }
  EXPECT_NEAR(length, p.length, 1e-12);
}

TEST(OctileAstar, EmptyGridCornerToCornerIsFourDiagonals) {
  const FreeRaster r = raster(5, 5, {});
  const auto p = octile_astar(r, {0, 0}, {4, 4});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->length, 4.0 * kSqrt2, 1e-12);
  EXPECT_EQ(p->cells.size(), 5u);
  EXPECT_EQ(p->cells.front(), (GridCell{0, 0}));
  EXPECT_EQ(p->cells.back(), (GridCell{4, 4}));
  expect_valid_path(r, *p);
}

TEST(OctileAstar, KnightMoveIsOneStraightAndOneDiagonal) {
  const auto p = octile_astar(raster(5, 5, {}), {0, 0}, {2, 1});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->length, 1.0 + kSqrt2, 1e-12);
}

TEST(OctileAstar, StartEqualsGoalIsZero) {
  const auto p = octile_astar(raster(3, 3, {}), {1, 1}, {1, 1});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->length, 0.0);
  EXPECT_EQ(p->cells.size(), 1u);
}

TEST(OctileAstar, WallForcesADetourOverTheTop) {
  // Column x = 2 blocked for y = 0..3; the only way from (0,0) to (4,0) is through (2,4), entered
  // from (1,4) and left to (3,4) (the diagonals would cut the wall's corner (2,3)):
  // octile (0,0)-(1,4) = 3 + sqrt2, then 2 straight, then (3,4)-(4,0) = 3 + sqrt2.
  const FreeRaster r = raster(5, 5, {{2, 0}, {2, 1}, {2, 2}, {2, 3}});
  const auto p = octile_astar(r, {0, 0}, {4, 0});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->length, 8.0 + 2.0 * kSqrt2, 1e-12);
  expect_valid_path(r, *p);
}

TEST(OctileAstar, RefusesToCutACorner) {
  // One blocked neighbour: the diagonal (0,0)-(1,1) would graze it, so two straight steps.
  const auto p = octile_astar(raster(2, 2, {{1, 0}}), {0, 0}, {1, 1});
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->length, 2.0, 1e-12);
  // Both neighbours blocked: the cells touch only at a corner, so there is no path.
  EXPECT_FALSE(octile_astar(raster(2, 2, {{1, 0}, {0, 1}}), {0, 0}, {1, 1}));
}

TEST(OctileAstar, UnreachableBlockedOrOutside) {
  const FreeRaster wall = raster(5, 5, {{2, 0}, {2, 1}, {2, 2}, {2, 3}, {2, 4}});
  EXPECT_FALSE(octile_astar(wall, {0, 0}, {4, 4}));
  EXPECT_FALSE(octile_astar(wall, {0, 0}, {2, 2}));  // goal blocked
  EXPECT_FALSE(octile_astar(wall, {2, 0}, {0, 0}));  // start blocked
  EXPECT_FALSE(octile_astar(wall, {0, 0}, {5, 0}));  // outside
  EXPECT_FALSE(octile_astar(wall, {-1, 0}, {0, 0}));
}

TEST(OctileAstar, MatchesTheOctileDistanceInOpenSpaceAndIsDeterministic) {
  const FreeRaster r = raster(40, 30, {});
  const auto a = octile_astar(r, {3, 4}, {37, 11});
  const auto b = octile_astar(r, {3, 4}, {37, 11});
  ASSERT_TRUE(a && b);
  EXPECT_NEAR(a->length, 27.0 + 7.0 * kSqrt2, 1e-9);
  EXPECT_EQ(a->cells, b->cells);
}

// The MovingAI benchmark's own optima (octile, no corner cutting), row by row: octile_astar on the
// map's cells, and scenario_optimum's octile length on the map as a world (1 m cells, r = 0.1 m, so
// every free cell's centre is free: its clearance is at least half a cell).
TEST(OctileAstar, MatchesEveryMovingAiScenOptimum) {
  const std::filesystem::path dir =
      std::filesystem::path(FLOORNAV_TEST_DATA_DIR) / "maps" / "movingai-mapf";
  for (const char* name : {"room-32-32-4", "den312d"}) {
    SCOPED_TRACE(name);
    const OccupancyGrid g = load_movingai_map(dir / (std::string(name) + ".map"), 1.0);
    FreeRaster r;
    r.width = g.width();
    r.height = g.height();
    for (int y = 0; y < g.height(); ++y)
      for (int x = 0; x < g.width(); ++x) r.free.push_back(g.occupied(x, y) ? 0 : 1);
    WorldDesc d;
    d.grid = std::make_shared<const OccupancyGrid>(g);
    const World w(d);
    const auto rows = load_movingai_scen(dir / (std::string(name) + "-random-1.scen"));
    ASSERT_GT(rows.size(), 100u);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const MovingAiCase& c = rows[i];
      const GridCell s{c.start_x, c.height - 1 - c.start_y}, t{c.goal_x, c.height - 1 - c.goal_y};
      const auto p = octile_astar(r, s, t);
      ASSERT_TRUE(p) << "row " << i;
      EXPECT_NEAR(p->length, c.optimal_length, 1e-6) << "row " << i;
      if (i % 10 == 0) {  // the whole pipeline, on a sample of rows
        const std::array<Vec2, 1> goal{movingai_cell_center(c.goal_x, c.goal_y, c.height, 1.0)};
        const Optimum o = scenario_optimum(
            w, 0.1, movingai_cell_center(c.start_x, c.start_y, c.height, 1.0), goal);
        ASSERT_EQ(o.status, OptimumStatus::Found) << "row " << i;
        EXPECT_NEAR(o.octile_length, c.optimal_length, 1e-6) << "row " << i;
        EXPECT_LE(o.length, o.octile_length + 1e-9);
        EXPECT_GE(
            o.length,
            (goal[0] - movingai_cell_center(c.start_x, c.start_y, c.height, 1.0)).norm() - 1e-9);
      }
    }
  }
}

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

// --- the optimum of a scenario ------------------------------------------------------------------

World gap_world(double gap) {
  // Bounds 4 x 2 m; a wall at x in [1.9, 2.1] across, with an opening `gap` wide around y = 1.
  WorldDesc d;
  d.bounds = Box2{{0.0, 0.0}, {4.0, 2.0}};
  const double lo = 1.0 - gap / 2.0, hi = 1.0 + gap / 2.0;
  d.polygons = {{{1.9, 0.0}, {2.1, 0.0}, {2.1, lo}, {1.9, lo}},
                {{1.9, hi}, {2.1, hi}, {2.1, 2.0}, {1.9, 2.0}}};
  return World(d);
}

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

TEST(ScenarioOptimum, StraightThroughAGapWiderThanTheRobot) {
  // Gap 0.3 m, r = 0.1 m: cell centres on the line y = 1 +- 0.025 have clearance 0.125 > r.
  const World w = gap_world(0.3);
  const std::array<Vec2, 1> goal{Vec2(3.5, 1.0)};
  const Optimum o = scenario_optimum(w, 0.1, {0.5, 1.0}, goal);
  ASSERT_EQ(o.status, OptimumStatus::Found) << to_string(o.status);
  EXPECT_DOUBLE_EQ(o.cell_size, 0.05);
  EXPECT_EQ(o.width, 80);
  EXPECT_EQ(o.height, 40);
  EXPECT_NEAR(o.length, 3.0, 1e-9);
  EXPECT_GE(o.octile_length, o.length);
  // The octile path joins the exact points to the cell centres half a diagonal away.
  EXPECT_NEAR(o.octile_length, 3.0 + 0.05 * std::sqrt(2.0), 1e-9);
}

TEST(ScenarioOptimum, InflationClosesAGapNarrowerThanTheDiameter) {
  // Gap 0.3 m < 2 r = 0.4 m: no cell in the opening keeps 0.2 m of clearance.
  const World w = gap_world(0.3);
  const std::array<Vec2, 1> goal{Vec2(3.5, 1.0)};
  EXPECT_EQ(scenario_optimum(w, 0.2, {0.5, 1.0}, goal).status, OptimumStatus::Unreachable);
  // Gap 0.5 m > 0.4 m: open again.
  EXPECT_EQ(scenario_optimum(gap_world(0.5), 0.2, {0.5, 1.0}, goal).status, OptimumStatus::Found);
}

TEST(ScenarioOptimum, GoesThroughEveryGoalInOrder) {
  WorldDesc d;
  d.bounds = Box2{{0.0, 0.0}, {10.0, 10.0}};
  const World w(d);
  const std::array<Vec2, 2> goals{Vec2(5.0, 1.0), Vec2(5.0, 5.0)};
  const Optimum o = scenario_optimum(w, 0.1, {1.0, 1.0}, goals);
  ASSERT_EQ(o.status, OptimumStatus::Found);
  EXPECT_NEAR(o.length, 8.0, 1e-9);
  // The route in the world: start, the first goal (a corner), the second goal.
  ASSERT_EQ(o.path.size(), 3u);
  EXPECT_NEAR((o.path[0] - Vec2(1.0, 1.0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((o.path[1] - goals[0]).norm(), 0.0, 1e-12);
  EXPECT_NEAR((o.path[2] - goals[1]).norm(), 0.0, 1e-12);
  // Without string pulling, an oblique leg keeps its octile length.
  const std::array<Vec2, 1> far{Vec2(8.0, 4.0)};
  OptimumOptions octile_only;
  octile_only.smooth = false;
  const Optimum s = scenario_optimum(w, 0.1, {1.0, 1.0}, far);
  const Optimum q = scenario_optimum(w, 0.1, {1.0, 1.0}, far, octile_only);
  ASSERT_EQ(s.status, OptimumStatus::Found);
  ASSERT_EQ(q.status, OptimumStatus::Found);
  EXPECT_NEAR(s.length, std::sqrt(58.0), 1e-9);
  EXPECT_NEAR(q.length, 4.0 + 3.0 * kSqrt2 + 0.05 * kSqrt2, 1e-9);
  EXPECT_EQ(q.length, q.octile_length);
}

TEST(ScenarioOptimum, UnboundedWorldGoesRoundTheObstacle) {
  // A disc of radius 1 straight between start and goal, no bounds: the margin lets the path pass
  // it; the true shortest path for r = 0.1 hugs a circle of radius 1.1 (two tangents and an arc):
  // 2 sqrt(3^2 - 1.1^2) + 1.1 (pi - 2 acos(1.1 / 3)) = 6.408.
  WorldDesc d;
  d.circles = {Circle{{0.0, 0.0}, 1.0}};
  const World w(d);
  const std::array<Vec2, 1> goal{Vec2(3.0, 0.0)};
  const Optimum o = scenario_optimum(w, 0.1, {-3.0, 0.0}, goal);
  ASSERT_EQ(o.status, OptimumStatus::Found);
  const double exact =
      2.0 * std::sqrt(9.0 - 1.21) + 1.1 * (std::numbers::pi - 2.0 * std::acos(1.1 / 3.0));
  EXPECT_GT(o.length, exact - 0.05);  // a cell-centre raster can undercut by under a cell
  EXPECT_LT(o.length, exact * 1.02);  // string pulling leaves it within 2 %
  EXPECT_GT(o.octile_length, o.length);
}

TEST(ScenarioOptimum, GridWorldUsesTheMapsOwnCells) {
  // 10 x 10 cells of 0.5 m at (-1, 2); cell (4, 0..8) occupied: a wall with a gap at the top.
  std::vector<std::uint8_t> occ(100, 0);
  for (int y = 0; y <= 8; ++y) occ[static_cast<std::size_t>(y) * 10 + 4] = 1;
  const OccupancyGrid g(10, 10, 0.5, Pose2{{-1.0, 2.0}, 0.0}, std::move(occ));
  WorldDesc d;
  d.grid = std::make_shared<const OccupancyGrid>(g);
  const World w(d);
  auto centre = [](int ix, int iy) { return Vec2(-1.0 + 0.5 * ix + 0.25, 2.0 + 0.5 * iy + 0.25); };
  const std::array<Vec2, 1> goal{centre(8, 0)};
  OptimumOptions octile_only;
  octile_only.smooth = false;
  const Optimum o = scenario_optimum(w, 0.1, centre(0, 0), goal, octile_only);
  ASSERT_EQ(o.status, OptimumStatus::Found) << to_string(o.status);
  EXPECT_EQ(o.cell_size, 0.5);
  EXPECT_EQ(o.width, 10);
  // (0,0)-(3,9): 6 + 3 sqrt2; (3,9)-(5,9): 2; (5,9)-(8,0): 6 + 3 sqrt2; in 0.5 m cells.
  EXPECT_NEAR(o.length, 0.5 * (14.0 + 6.0 * kSqrt2), 1e-9);
  // Body radius 0.3 m: centres next to the wall (clearance 0.25) are blocked, and so is the gap.
  EXPECT_EQ(scenario_optimum(w, 0.3, centre(0, 0), goal).status, OptimumStatus::Unreachable);
}

TEST(ScenarioOptimum, StartInsideAWallSnapsToANearbyFreeCell) {
  const World w = gap_world(0.5);
  const std::array<Vec2, 1> goal{Vec2(3.5, 1.0)};
  // 2 cm into the wall at x = 1.9: the nearest free centre is a few cells left.
  const Optimum o = scenario_optimum(w, 0.1, {1.92, 0.3}, goal);
  ASSERT_EQ(o.status, OptimumStatus::Found);
  EXPECT_GT(o.length, 1.5);
  // Mid-wall: the nearest centre with clearance > r is more than 3 cells away, so none.
  EXPECT_EQ(scenario_optimum(w, 0.1, {2.0, 0.3}, goal).status, OptimumStatus::NoFreeCell);
  // A goal outside the bounds.
  const std::array<Vec2, 1> outside{Vec2(9.0, 1.0)};
  EXPECT_EQ(scenario_optimum(w, 0.1, {0.5, 1.0}, outside).status, OptimumStatus::NoFreeCell);
}

TEST(ScenarioOptimum, HugeWorldFailsFastInsteadOfBuildingTheRaster) {
  WorldDesc d;
  d.bounds = Box2{{0.0, 0.0}, {1000.0, 1000.0}};
  const World w(d);
  const std::array<Vec2, 1> goal{Vec2(900.0, 900.0)};
  EXPECT_EQ(scenario_optimum(w, 0.1, {1.0, 1.0}, goal).status, OptimumStatus::RasterTooLarge);
  // A bigger robot tolerates coarser cells: at most 1e6 cells of about 1 m for r = 1.5 m.
  OptimumOptions small;
  small.max_cells = 1'000'000;
  const Optimum o = scenario_optimum(w, 1.5, {2.0, 2.0}, goal, small);
  ASSERT_EQ(o.status, OptimumStatus::Found) << to_string(o.status);
  EXPECT_LE(static_cast<double>(o.width) * o.height, 1e6);
  EXPECT_GT(o.cell_size, 1.0);
  EXPECT_NEAR(o.length, 898.0 * std::sqrt(2.0), 1e-6);
}

TEST(ScenarioOptimum, BadInputIsNoOptimumNotNaN) {
  const World w = gap_world(0.5);
  const std::array<Vec2, 1> goal{Vec2(3.5, 1.0)};
  EXPECT_EQ(scenario_optimum(w, 0.1, {NAN, 1.0}, goal).status, OptimumStatus::InvalidInput);
  EXPECT_EQ(scenario_optimum(w, -1.0, {0.5, 1.0}, goal).status, OptimumStatus::InvalidInput);
  EXPECT_EQ(scenario_optimum(w, 0.1, {0.5, 1.0}, {}).status, OptimumStatus::InvalidInput);
}

}  // namespace
}  // namespace floornav
