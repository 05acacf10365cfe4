// The rrt_connect planner's search (OMPL's RRT-Connect on a FreeRaster): linking floornav::ompl
// installs it; its path stays on free cells and joins start to goal, it is the same for the same
// seed (and differs for another), an unreachable goal gives no path within the budget, and
// blocked ends give none at all.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "floornav/nav/planner_params.hpp"
#include "floornav/nav/sampling_planner.hpp"
#include "floornav/ompl/rrt_connect.hpp"
#include "floornav/planning/line_of_sight.hpp"

namespace floornav {
namespace {

// 40 x 30 cells, a wall across x = 20 with a 3-cell gap at rows 24..26 (far from the straight
// line start -> goal, so a path must bend through it).
FreeRaster wall_with_gap(bool gap = true) {
  FreeRaster r;
  r.width = 40;
  r.height = 30;
  r.free.assign(static_cast<std::size_t>(r.width * r.height), 1);
  for (int y = 0; y < r.height; ++y) {
    if (gap && y >= 24 && y <= 26) continue;
    for (int x = 19; x <= 20; ++x) r.free[static_cast<std::size_t>(y * r.width + x)] = 0;
  }
  return r;
}

constexpr GridCell kStart{5, 5};
constexpr GridCell kGoal{34, 5};

// A program that links floornav::ompl (this test, floornav::floornav's users) has the planner
// without a call: it is installed before main().
TEST(RrtConnectPath, LinkingFloornavOmplInstallsItForThePlanner) {
  EXPECT_EQ(rrt_connect_search(), &rrt_connect_path);
}

TEST(RrtConnectPath, CrossesTheWallThroughTheGapOnFreeCellsOnly) {
  const FreeRaster r = wall_with_gap();
  std::vector<Vec2> path;
  ASSERT_TRUE(rrt_connect_path(r, kStart, kGoal, 7, 20000, path));
  ASSERT_GE(path.size(), 3u) << "the straight line is blocked: the path must bend";
  EXPECT_EQ(path.front(), Vec2(5.5, 5.5));
  EXPECT_EQ(path.back(), Vec2(34.5, 5.5));
  bool through_gap = false;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Vec2& p = path[i];
    EXPECT_TRUE(r.is_free(static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y()))))
        << "vertex " << i;
    if (i + 1 < path.size()) {
      EXPECT_TRUE(line_of_sight(r, p, path[i + 1])) << "segment " << i;
      // Where a segment crosses the wall (x = 19..21), it is in the gap.
      const Vec2& q = path[i + 1];
      if ((p.x() - 20.0) * (q.x() - 20.0) < 0.0) {
        const double y = p.y() + (q.y() - p.y()) * (20.0 - p.x()) / (q.x() - p.x());
        EXPECT_GE(y, 24.0);
        EXPECT_LE(y, 27.0);
        through_gap = true;
      }
    }
  }
  EXPECT_TRUE(through_gap);
}

TEST(RrtConnectPath, SameSeedSamePathBitForBitAnotherSeedAnotherPath) {
  const FreeRaster r = wall_with_gap();
  std::vector<Vec2> a, b, c;
  ASSERT_TRUE(rrt_connect_path(r, kStart, kGoal, 42, 20000, a));
  ASSERT_TRUE(rrt_connect_path(r, kStart, kGoal, 42, 20000, b));
  ASSERT_TRUE(rrt_connect_path(r, kStart, kGoal, 43, 20000, c));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].x(), b[i].x()) << i;
    EXPECT_EQ(a[i].y(), b[i].y()) << i;
  }
  // The seed is really used: another seed samples another tree (the interior vertices differ).
  EXPECT_NE(a, c);
}

TEST(RrtConnectPath, UnreachableGoalGivesNoPathWithinTheBudget) {
  const FreeRaster r = wall_with_gap(false);
  std::vector<Vec2> path{Vec2(1, 1)};
  EXPECT_FALSE(rrt_connect_path(r, kStart, kGoal, 7, 2000, path));
  EXPECT_TRUE(path.empty());
}

TEST(RrtConnectPath, BlockedEndsOrNoBudgetGiveNoPath) {
  const FreeRaster r = wall_with_gap();
  std::vector<Vec2> path;
  EXPECT_FALSE(rrt_connect_path(r, GridCell{19, 5}, kGoal, 7, 2000, path));
  EXPECT_FALSE(rrt_connect_path(r, kStart, GridCell{20, 5}, 7, 2000, path));
  EXPECT_FALSE(rrt_connect_path(r, kStart, GridCell{40, 5}, 7, 2000, path));  // outside
  EXPECT_FALSE(rrt_connect_path(r, kStart, kGoal, 7, 0, path));
  // A budget too small to cross: no path, not a path through the wall.
  EXPECT_FALSE(rrt_connect_path(r, kStart, kGoal, 7, 1, path));
}

// The sample limit bounds a plan's time whoever calls the planner, not only what scenario
// validation lets through: a budget above it is refused before any sampling, even on an
// enclosed goal (where it would all be spent); the limit itself is a budget like any other.
TEST(RrtConnectPath, RefusesABudgetAboveTheSampleLimitBeforeAnyWork) {
  const FreeRaster enclosed = wall_with_gap(false);
  std::vector<Vec2> path{Vec2(1, 1)};
  for (const int budget : {kMaxRrtConnectSamples + 1, std::numeric_limits<int>::max()}) {
    try {
      rrt_connect_path(enclosed, kStart, kGoal, 7, budget, path);
      ADD_FAILURE() << "a budget of " << budget << " samples was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("above the limit of 200000"), std::string::npos)
          << e.what();
    }
    EXPECT_TRUE(path.empty()) << "the output is cleared even when the call is refused";
  }
  const FreeRaster open = wall_with_gap();
  ASSERT_TRUE(rrt_connect_path(open, kStart, kGoal, 7, kMaxRrtConnectSamples, path));
  EXPECT_EQ(path.back(), Vec2(34.5, 5.5));
}

}  // namespace
}  // namespace floornav
