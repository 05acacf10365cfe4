// The optimum of a scenario (start through every goal, a disc robot on a raster of the world), on
// hand-worked cases and the MovingAI benchmark's own optima.
#include "floornav/runner/scenario_optimum.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/io/movingai_map.hpp"
#include "floornav/planning/octile_astar.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"
#include "planning/planning_test_support.hpp"

namespace floornav {
namespace {

using test::gap_world;

const double kSqrt2 = std::sqrt(2.0);

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

// A raster built once per world serves every route there with the result of building it anew:
// routes through a bounded world of polygons and through a map, routes that fail (unreachable,
// no free cell, bad points); a raster too large or a bad radius carries its status to every
// route; a world without bounds or map has no route-free raster.
TEST(ScenarioOptimum, ARasterBuiltOncePerWorldGivesEveryRoutesOptimum) {
  auto same = [](const Optimum& a, const Optimum& b) {
    EXPECT_EQ(a.status, b.status);
    EXPECT_EQ(a.length, b.length);
    EXPECT_EQ(a.octile_length, b.octile_length);
    EXPECT_EQ(a.cell_size, b.cell_size);
    EXPECT_EQ(a.width, b.width);
    EXPECT_EQ(a.height, b.height);
    EXPECT_EQ(a.path, b.path);
  };
  const World gap = gap_world(0.5);
  std::vector<std::uint8_t> occ(100, 0);
  for (int y = 0; y <= 8; ++y) occ[static_cast<std::size_t>(y) * 10 + 4] = 1;
  WorldDesc gd;
  gd.grid =
      std::make_shared<const OccupancyGrid>(10, 10, 0.5, Pose2{{-1.0, 2.0}, 0.3}, std::move(occ));
  const World map(gd);
  Rng rng(9);
  int found = 0, failed = 0;
  for (const World* w : {&gap, &map}) {
    for (const double r : {0.0, 0.1, 0.2}) {
      OptimumRaster raster;
      ASSERT_TRUE(build_optimum_raster(*w, r, {}, raster));
      const Box2 e = w->extent();
      for (int k = 0; k < 30; ++k) {
        auto point = [&] {
          return Vec2(rng.uniform(e.min.x() - 0.5, e.max.x() + 0.5),
                      rng.uniform(e.min.y() - 0.5, e.max.y() + 0.5));
        };
        const Vec2 start = k == 0 ? Vec2(NAN, 0.0) : point();
        const std::vector<Vec2> goals = {point(), point()};
        const Optimum fresh = scenario_optimum(*w, r, start, goals);
        same(scenario_optimum(raster, start, goals), fresh);
        (fresh.status == OptimumStatus::Found ? found : failed) += 1;
      }
    }
  }
  EXPECT_GT(found, 30);
  EXPECT_GT(failed, 30);
  // Statuses of the raster itself.
  WorldDesc huge;
  huge.bounds = Box2{{0.0, 0.0}, {1000.0, 1000.0}};
  const World hw(huge);
  const std::array<Vec2, 1> goal{Vec2(900.0, 900.0)};
  OptimumRaster raster;  // reused across worlds, as a batch does
  ASSERT_TRUE(build_optimum_raster(hw, 0.1, {}, raster));
  EXPECT_EQ(scenario_optimum(raster, {1.0, 1.0}, goal).status, OptimumStatus::RasterTooLarge);
  ASSERT_TRUE(build_optimum_raster(gap, -1.0, {}, raster));
  EXPECT_EQ(scenario_optimum(raster, {0.5, 1.0}, goal).status, OptimumStatus::InvalidInput);
  ASSERT_TRUE(build_optimum_raster(gap, 0.1, {}, raster));
  const std::array<Vec2, 1> across{Vec2(3.5, 1.0)};
  same(scenario_optimum(raster, {0.5, 1.0}, across),
       scenario_optimum(gap, 0.1, {0.5, 1.0}, across));
  WorldDesc open;
  open.circles = {Circle{{1.0, 1.0}, 0.3}};
  EXPECT_FALSE(build_optimum_raster(World(open), 0.1, {}, raster));
}

}  // namespace
}  // namespace floornav
