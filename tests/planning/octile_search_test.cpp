// Octile A*, its reusable search and jump point search, on hand-worked cases and against a plain
// priority-queue A*.
#include "floornav/planning/octile_astar.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <queue>
#include <tuple>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/planning/jump_point_search.hpp"
#include "planning/planning_test_support.hpp"

namespace floornav {
namespace {

using test::raster;

const double kSqrt2 = std::sqrt(2.0);

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

}  // namespace
}  // namespace floornav
