// Octile A*, raster line of sight, string pulling and the scenario optimum, on hand-worked cases.
#include "floornav/world/shortest_path.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <numbers>
#include <optional>
#include <queue>
#include <tuple>
#include <vector>

#include "floornav/core/rng.hpp"
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

/// Blocks `count` random rectangles of `min_side` to `min_side + side_range` cells (clipped to the
/// raster) out of r, drawing from rng corner x, corner y, width, height, block by block.
void block_out(FreeRaster& r, Rng& rng, int count, int min_side, double side_range) {
  for (int k = 0; k < count; ++k) {
    const int x0 = static_cast<int>(rng.uniform(0.0, r.width - 1e-9));
    const int y0 = static_cast<int>(rng.uniform(0.0, r.height - 1e-9));
    const int bw = min_side + static_cast<int>(rng.uniform(0.0, side_range));
    const int bh = min_side + static_cast<int>(rng.uniform(0.0, side_range));
    for (int y = y0; y < std::min(r.height, y0 + bh); ++y)
      for (int x = x0; x < std::min(r.width, x0 + bw); ++x)
        r.free[static_cast<std::size_t>(y * r.width + x)] = 0;
  }
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

// GridSearch keeps its buffers between searches; every search must be the one a fresh search
// makes, whatever came before it (a larger raster, a failed search, a blocked goal).
TEST(GridSearch, ReusedSearchEqualsAFreshOneEveryTime) {
  const FreeRaster big = raster(40, 30, {{10, 0}, {10, 1}, {10, 2}, {10, 3}, {10, 4}, {10, 5}});
  const FreeRaster wall = raster(5, 3, {{2, 0}, {2, 1}, {2, 2}});
  const FreeRaster small = raster(6, 6, {{2, 2}, {3, 2}, {2, 3}});
  GridSearch search;
  GridPath path;
  struct Case {
    const FreeRaster* r;
    GridCell s, g;
  };
  const Case cases[] = {{&big, {0, 0}, {39, 29}}, {&small, {0, 0}, {5, 5}}, {&wall, {0, 0}, {4, 0}},
                        {&big, {3, 4}, {37, 11}}, {&small, {5, 0}, {0, 5}}, {&big, {0, 0}, {12, 0}},
                        {&wall, {0, 0}, {2, 0}},  {&small, {0, 0}, {5, 5}}};
  for (const Case& c : cases) {
    const auto fresh = octile_astar(*c.r, c.s, c.g);
    const bool found = search.search(*c.r, c.s, c.g, path);
    ASSERT_EQ(found, fresh.has_value());
    if (!found) {
      EXPECT_TRUE(path.cells.empty());
      continue;
    }
    EXPECT_EQ(path.cells, fresh->cells);
    EXPECT_EQ(path.length, fresh->length);
    expect_valid_path(*c.r, path);
    EXPECT_GT(search.expanded(), 0u);
  }
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

// Searches reuse their working memory (per thread, nothing cleared between searches): a search
// after others on larger and smaller rasters, some failing half-way, finds what it found first.
TEST(OctileAstar, ASearchAfterOthersOnOtherRastersFindsTheSamePath) {
  Rng rng(5);
  std::vector<std::array<int, 2>> blocked;
  for (int k = 0; k < 300; ++k)
    blocked.push_back(
        {static_cast<int>(rng.uniform(0.0, 40.0)), static_cast<int>(rng.uniform(0.0, 30.0))});
  FreeRaster r = raster(40, 30, {});
  for (const auto& [x, y] : blocked)
    if ((x > 1 || y > 1) && (x < 38 || y < 28)) r.free[static_cast<std::size_t>(y * 40 + x)] = 0;
  const auto first = octile_astar(r, {0, 0}, {39, 29});
  ASSERT_TRUE(first);
  EXPECT_TRUE(octile_astar(raster(200, 150, {}), {0, 0}, {199, 149}));
  EXPECT_FALSE(
      octile_astar(raster(5, 5, {{2, 0}, {2, 1}, {2, 2}, {2, 3}, {2, 4}}), {0, 0}, {4, 4}));
  EXPECT_TRUE(octile_astar(raster(7, 3, {}), {6, 2}, {0, 0}));
  const auto again = octile_astar(r, {0, 0}, {39, 29});
  ASSERT_TRUE(again);
  EXPECT_EQ(again->cells, first->cells);
  EXPECT_EQ(again->length, first->length);
}

// The search as it was first written (std::priority_queue over (f, -g, index), fresh arrays):
// the oracle for the reused buffers and the radix heap of octile_astar.
std::optional<GridPath> reference_astar(const FreeRaster& r, GridCell start, GridCell goal) {
  if (!r.is_free(start.x, start.y) || !r.is_free(goal.x, goal.y)) return std::nullopt;
  const std::size_t w = static_cast<std::size_t>(r.width),
                    n = w * static_cast<std::size_t>(r.height);
  auto h = [&](int x, int y) {
    const int ax = std::abs(goal.x - x), ay = std::abs(goal.y - y);
    return (std::max(ax, ay) - std::min(ax, ay)) + kSqrt2 * std::min(ax, ay);
  };
  std::vector<double> g(n, INFINITY);
  std::vector<std::int64_t> parent(n, -1);
  std::vector<char> closed(n, 0);
  using Entry = std::tuple<double, double, std::size_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  const std::size_t s = static_cast<std::size_t>(start.y) * w + static_cast<std::size_t>(start.x);
  const std::size_t t = static_cast<std::size_t>(goal.y) * w + static_cast<std::size_t>(goal.x);
  g[s] = 0.0;
  open.emplace(h(start.x, start.y), -0.0, s);
  const int dx[8] = {1, -1, 0, 0, 1, 1, -1, -1}, dy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  while (!open.empty()) {
    const std::size_t u = std::get<2>(open.top());
    open.pop();
    if (closed[u]) continue;
    closed[u] = 1;
    if (u == t) break;
    const int ux = static_cast<int>(u % w), uy = static_cast<int>(u / w);
    for (int k = 0; k < 8; ++k) {
      const int vx = ux + dx[k], vy = uy + dy[k];
      const bool diagonal = k >= 4;
      if (!r.is_free(vx, vy) ||
          (diagonal && (!r.is_free(ux + dx[k], uy) || !r.is_free(ux, uy + dy[k]))))
        continue;
      const std::size_t v = static_cast<std::size_t>(vy) * w + static_cast<std::size_t>(vx);
      const double gv = g[u] + (diagonal ? kSqrt2 : 1.0);
      if (!closed[v] && gv < g[v]) {
        g[v] = gv;
        parent[v] = static_cast<std::int64_t>(u);
        open.emplace(gv + h(vx, vy), -gv, v);
      }
    }
  }
  if (!closed[t]) return std::nullopt;
  GridPath p;
  p.length = g[t];
  for (std::int64_t v = static_cast<std::int64_t>(t); v >= 0;
       v = parent[static_cast<std::size_t>(v)])
    p.cells.push_back({static_cast<int>(v % static_cast<std::int64_t>(w)),
                       static_cast<int>(v / static_cast<std::int64_t>(w))});
  std::reverse(p.cells.begin(), p.cells.end());
  return p;
}

// On random rasters (open to cluttered, from 1 x 1 to 90 x 70, starts and goals anywhere, some
// blocked or cut off), octile_astar finds the very path the plain search finds, cell for cell.
TEST(OctileAstar, RandomRastersGiveThePlainSearchsPathCellForCell) {
  Rng rng(77);
  int found = 0, none = 0;
  for (int trial = 0; trial < 400; ++trial) {
    FreeRaster r;
    r.width = 1 + static_cast<int>(rng.uniform(0.0, 90.0));
    r.height = 1 + static_cast<int>(rng.uniform(0.0, 70.0));
    const double blocked = rng.uniform(0.0, 0.45);
    r.free.resize(static_cast<std::size_t>(r.width * r.height));
    for (auto& c : r.free) c = rng.uniform() >= blocked;
    auto cell = [&] {
      return GridCell{static_cast<int>(rng.uniform(0.0, r.width - 1e-9)),
                      static_cast<int>(rng.uniform(0.0, r.height - 1e-9))};
    };
    const GridCell a = cell(), b = cell();
    const auto got = octile_astar(r, a, b), want = reference_astar(r, a, b);
    ASSERT_EQ(got.has_value(), want.has_value()) << trial;
    if (!want) {
      ++none;
      continue;
    }
    ++found;
    EXPECT_EQ(got->cells, want->cells) << trial;
    EXPECT_EQ(got->length, want->length) << trial;
  }
  EXPECT_GT(found, 100);
  EXPECT_GT(none, 50);
}

// Open rasters with a few blocks, as the batch's floors are: wide plateaus of equal f (hundreds
// of open entries that tie, and f values an ulp apart after long sums of 1 and sqrt 2), where
// the open list keeps its ties in a sorted vector rather than a heap. Every search, fresh or on
// reused buffers, finds the plain search's path cell for cell and its length to the bit; the
// detours make it expand far more cells than the path has (the ties are really exercised).
TEST(OctileAstar, OpenRastersWithBlocksGiveThePlainSearchsPathCellForCell) {
  Rng rng(2026);
  GridSearch search;
  GridPath reused;
  int detours = 0;
  for (int trial = 0; trial < 40; ++trial) {
    FreeRaster r;
    r.width = 120 + static_cast<int>(rng.uniform(0.0, 130.0));
    r.height = 100 + static_cast<int>(rng.uniform(0.0, 120.0));
    r.free.assign(static_cast<std::size_t>(r.width * r.height), 1);
    block_out(r, rng, 3 + static_cast<int>(rng.uniform(0.0, 25.0)), 2, 40.0);
    auto free_cell = [&] {
      for (;;) {
        const GridCell c{static_cast<int>(rng.uniform(0.0, r.width - 1e-9)),
                         static_cast<int>(rng.uniform(0.0, r.height - 1e-9))};
        if (r.is_free(c.x, c.y)) return c;
      }
    };
    const GridCell a = free_cell(), b = free_cell();
    const auto want = reference_astar(r, a, b);
    const auto got = octile_astar(r, a, b);
    ASSERT_EQ(got.has_value(), want.has_value()) << trial;
    ASSERT_EQ(search.search(r, a, b, reused), want.has_value()) << trial;
    if (!want) continue;
    EXPECT_EQ(got->cells, want->cells) << trial;
    EXPECT_EQ(got->length, want->length) << trial;
    EXPECT_EQ(reused.cells, want->cells) << trial;
    EXPECT_EQ(reused.length, want->length) << trial;
    if (search.expanded() > 4 * want->cells.size()) ++detours;
  }
  EXPECT_GT(detours, 10);
}

// A path of octile moves between free cells that cuts no corner, from `a` to `b`; its length.
double checked_octile_length(const FreeRaster& r, const std::vector<GridCell>& cells, GridCell a,
                             GridCell b) {
  EXPECT_FALSE(cells.empty());
  if (cells.empty()) return -1.0;
  EXPECT_EQ(cells.front(), a);
  EXPECT_EQ(cells.back(), b);
  double length = 0.0;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    EXPECT_TRUE(r.is_free(cells[i].x, cells[i].y)) << i;
    if (i == 0) continue;
    const int dx = cells[i].x - cells[i - 1].x, dy = cells[i].y - cells[i - 1].y;
    EXPECT_TRUE(std::abs(dx) <= 1 && std::abs(dy) <= 1 && (dx != 0 || dy != 0)) << i;
    if (dx != 0 && dy != 0) {
      EXPECT_TRUE(r.is_free(cells[i - 1].x + dx, cells[i - 1].y)) << "cuts a corner at " << i;
      EXPECT_TRUE(r.is_free(cells[i - 1].x, cells[i - 1].y + dy)) << "cuts a corner at " << i;
      length += kSqrt2;
    } else {
      length += 1.0;
    }
  }
  return length;
}

// Jump point search finds a path exactly as short as the plain search's (to the rounding of the
// sums), made of legal moves, and none where there is none: on the random rasters (cluttered,
// with cut-off cells) and on open rasters with blocks (long runs, many equal paths), where it
// expands far fewer cells' worth of jump points than A* expands cells.
TEST(OctileJumpPointSearch, AsShortAsThePlainSearchOnRandomRasters) {
  Rng rng(4242);
  int found = 0, none = 0, other_path = 0;
  for (int trial = 0; trial < 600; ++trial) {
    FreeRaster r;
    const bool open = trial % 2 == 1;
    r.width = open ? 60 + static_cast<int>(rng.uniform(0.0, 140.0))
                   : 1 + static_cast<int>(rng.uniform(0.0, 90.0));
    r.height = open ? 50 + static_cast<int>(rng.uniform(0.0, 120.0))
                    : 1 + static_cast<int>(rng.uniform(0.0, 70.0));
    r.free.assign(static_cast<std::size_t>(r.width * r.height), 1);
    if (open) {
      block_out(r, rng, 2 + static_cast<int>(rng.uniform(0.0, 25.0)), 1, 30.0);
    } else {
      const double blocked = rng.uniform(0.0, 0.45);
      for (auto& c : r.free) c = rng.uniform() >= blocked;
    }
    const GridCell a{static_cast<int>(rng.uniform(0.0, r.width - 1e-9)),
                     static_cast<int>(rng.uniform(0.0, r.height - 1e-9))};
    const GridCell b{static_cast<int>(rng.uniform(0.0, r.width - 1e-9)),
                     static_cast<int>(rng.uniform(0.0, r.height - 1e-9))};
    const auto want = reference_astar(r, a, b);
    const auto got = octile_jump_point_search(r, a, b);
    ASSERT_EQ(got.has_value(), want.has_value()) << trial;
    if (!want) {
      ++none;
      continue;
    }
    ++found;
    EXPECT_NEAR(got->length, want->length, 1e-9 * (1.0 + want->length)) << trial;
    EXPECT_NEAR(checked_octile_length(r, got->cells, a, b), want->length,
                1e-9 * (1.0 + want->length))
        << trial;
    if (got->cells != want->cells) ++other_path;
  }
  EXPECT_GT(found, 300);
  EXPECT_GT(none, 30);
  EXPECT_GT(other_path, 0);  // ties do go another way: its paths are its own
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
