// OccupancyGrid::cast_fan on fine grids and long ranges (issue 14): the fan visits the occupied
// runs tile by tile and passes over whole tiles that no beam can still reach nearer than its hit.
// Every beam must stay bit for bit the plain cell-by-cell DDA's (cast_ray_cell_by_cell, the
// oracle), on the cave the peer benchmark uses (0.032 m cells, 180 beams, 8 m) and on real maps.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <utility>
#include <vector>

#include "../../bench/cave_map.hpp"
#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/io/ros_map.hpp"
#include "floornav/world/fan_index.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "support/bits.hpp"

namespace floornav {
namespace {

using test::bits;

// A lidar of n beams over `fov` (2 pi: a full turn, the last beam one step short of the first)
// centred on `heading`, angles wrapped as sensors wrap them.
void lidar(double heading, double fov, int n, std::vector<Vec2>& dirs,
           std::vector<double>& angles) {
  dirs.resize(n);
  angles.resize(n);
  const bool full = fov >= 2.0 * kPi;
  const double step = full ? fov / n : fov / (n - 1);
  for (int k = 0; k < n; ++k) {
    const double a = wrap_angle(heading - (full ? 0.0 : 0.5 * fov) + step * k);
    angles[k] = a;
    dirs[k] = Vec2(std::cos(a), std::sin(a));
  }
}

// Fans from `fans` free origins of `g` (some on cell corners and on the fan's tile borders),
// half of them 180 degrees wide and half full turns, each at one of `ranges`: every beam bit for
// bit the cell-by-cell walk. Returns the number of beams that hit something.
long expect_fans_match_oracle(const OccupancyGrid& g, Rng& rng, int fans,
                              const std::vector<double>& ranges, const char* what) {
  Vec2 lo, hi;
  g.world_extent(&lo, &hi);
  const double res = g.resolution();
  std::vector<Vec2> dirs;
  std::vector<double> angles, out;
  FanScratch scratch;
  long hits = 0;
  for (int f = 0; f < fans; ++f) {
    Vec2 p(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()));
    // Grid-aligned maps only (yaw 0): snap to a cell corner or a tile border.
    if (g.origin().theta == 0.0 && f % 4 == 1) {
      const Vec2 cell = (p - g.origin().position) / res;
      p = g.origin().position + Vec2(std::round(cell.x()), std::round(cell.y())) * res;
    }
    if (g.origin().theta == 0.0 && f % 4 == 2) {
      const Vec2 cell = (p - g.origin().position) / res;
      constexpr double tile = OccupancyGrid::FanIndex::kTile;
      p = g.origin().position + Vec2(tile * std::round(cell.x() / tile), cell.y()) * res;
    }
    if (!(g.clearance(p) > 0.0)) {
      --f;
      continue;
    }
    const double range = ranges[f % ranges.size()];
    lidar(rng.uniform(-kPi, kPi), f % 2 == 0 ? kPi : 2.0 * kPi, 180, dirs, angles);
    out.assign(dirs.size(), -1.0);
    g.cast_fan(p, dirs, angles, range, out, scratch);
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      const double oracle = g.cast_ray_cell_by_cell(p, dirs[k], range);
      if (oracle < range) ++hits;
      EXPECT_EQ(bits(out[k]), bits(oracle))
          << what << " fan " << f << " beam " << k << " from (" << p.x() << ", " << p.y()
          << ") angle " << angles[k] << " range " << range << ": fan " << out[k] << ", oracle "
          << oracle;
      if (::testing::Test::HasFailure()) return hits;
    }
  }
  return hits;
}

TEST(GridFanLongRange, MatchesTheCellByCellWalkOnTheCave) {
  const bench::CaveMap cave = bench::make_cave_map();
  Rng rng(14);
  const long hits = expect_fans_match_oracle(*cave.grid, rng, 600, {8.0, 3.5, 16.0, 30.0}, "cave");
  // The comparison means something only if most beams hit a wall (the cave is walled all round).
  EXPECT_GT(hits, 600 * 180 / 2);
}

TEST(GridFanLongRange, MatchesTheCellByCellWalkOnRealMaps) {
  const auto maps = std::filesystem::path(FLOORNAV_TEST_DATA_DIR) / "maps";
  const char* files[] = {"turtlebot3/map.yaml", "nav2-bringup/depot.yaml",
                         "ros-navigation-tutorials/lse_arena.yaml",
                         "aws-robomaker-small-warehouse/005/map.yaml"};
  Rng rng(15);
  for (const char* file : files) {
    const OccupancyGrid g = load_ros_map(maps / file);
    const long hits = expect_fans_match_oracle(g, rng, 150, {8.0, 30.0, 3.5}, file);
    ASSERT_FALSE(::testing::Test::HasFailure()) << file;
    EXPECT_GT(hits, 150 * 180 / 4) << file;
  }
}

// Turned grids (the fan works in the grid's frame: its centre line and its beams turned by the
// map's yaw), with half-turn and full-turn fans, on random walls and noise.
TEST(GridFanLongRange, MatchesTheCellByCellWalkOnTurnedRandomGrids) {
  Rng rng(16);
  for (int m = 0; m < 30; ++m) {
    const int w = 20 + static_cast<int>(rng.uniform(0.0, 200.0));
    const int h = 20 + static_cast<int>(rng.uniform(0.0, 200.0));
    const double density = std::pow(10.0, rng.uniform(-3.0, -1.0));
    std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * h);
    for (auto& c : cells) c = rng.uniform() < density ? 1 : 0;
    for (int k = 0; k < 6; ++k) {  // a few straight walls
      const bool column = rng.uniform() < 0.5;
      const int at = static_cast<int>(rng.uniform(0.0, column ? w : h));
      for (int i = 0; i < (column ? h : w); ++i)
        if (rng.uniform() < 0.9)
          cells[column ? static_cast<std::size_t>(i) * w + at
                       : static_cast<std::size_t>(at) * w + i] = 1;
    }
    const double yaw = m % 2 == 0 ? rng.uniform(-kPi, kPi) : 0.0;
    const OccupancyGrid g(w, h, 0.05, Pose2{Vec2(1.5, -0.7), yaw}, cells);
    expect_fans_match_oracle(g, rng, 40, {8.0, 2.0, 20.0}, "random grid");
    ASSERT_FALSE(::testing::Test::HasFailure()) << "grid " << m;
  }
}

// Worked by hand: a wall (column 40, rows 0..79) seen across a tile border, and a second wall
// behind it (column 60) that the first hides; the origin on the tile border y = 64.
TEST(GridFanLongRange, ANearWallHidesTheOneBehindIt) {
  constexpr int n = 80;
  std::vector<std::uint8_t> cells(n * n, 0);
  for (int y = 0; y < n; ++y) {
    cells[static_cast<std::size_t>(y) * n + 40] = 1;
    cells[static_cast<std::size_t>(y) * n + 60] = 1;
  }
  const OccupancyGrid g(n, n, 0.5, Pose2{Vec2(0.0, 0.0), 0.0}, cells);
  static_assert(OccupancyGrid::FanIndex::kTile == 64, "the origin below is on a tile border");
  const Vec2 o(5.5 * 0.5, 64.0 * 0.5);  // cell units (5.5, 64)
  std::vector<Vec2> dirs;
  std::vector<double> angles;
  lidar(0.0, kPi, 181, dirs, angles);  // 1 degree apart; beam 90 points along +x
  std::vector<double> out(dirs.size());
  g.cast_fan(o, dirs, angles, 100.0, out);
  // Along +x the walk enters column 40 at x = 40: 34.5 cells = 17.25 m, not column 60's 27.25 m.
  EXPECT_EQ(out[90], 17.25);
  // At 60 degrees: x = 40 is reached at t = 34.5 / cos 60 = 69 cells, y = 64 + 69 sin 60 = 123.8,
  // past the grid's top (80): that beam leaves the grid and reads the range.
  EXPECT_EQ(out[150], 100.0);
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    EXPECT_EQ(bits(out[k]), bits(g.cast_ray_cell_by_cell(o, dirs[k], 100.0))) << k;
    // Nothing reads the hidden wall's distance: every hit is on column 40's face.
    if (out[k] < 100.0) {
      EXPECT_NEAR((o.x() + out[k] * dirs[k].x()) / 0.5, 40.0, 1e-9) << k;
    }
  }
}

// Hollow outlines (the cave's blobs): the fan takes only the runs that walks from the origin's
// component of free cells can touch first, so the far side of an outline is left out from
// outside and everything outside it from inside. One-cell outlines: rectangles (4-connected),
// diamonds and circles (8-connected staircases, which walks cross only through their corners and
// there touch both cells), nested and touching ones; origins inside each pocket, on its cell
// corners and outside; turned grids too.
TEST(GridFanLongRange, MatchesTheCellByCellWalkInAndAroundHollowOutlines) {
  constexpr int n = 240;
  std::vector<std::uint8_t> cells(static_cast<std::size_t>(n) * n, 0);
  const auto set = [&](int x, int y) {
    if (x >= 0 && y >= 0 && x < n && y < n) cells[static_cast<std::size_t>(y) * n + x] = 1;
  };
  struct Pocket {
    int cx, cy;
  };
  std::vector<Pocket> pockets;
  const auto rectangle = [&](int x0, int y0, int x1, int y1) {
    for (int x = x0; x <= x1; ++x) set(x, y0), set(x, y1);
    for (int y = y0; y <= y1; ++y) set(x0, y), set(x1, y);
    pockets.push_back({(x0 + x1) / 2, (y0 + y1) / 2});
  };
  const auto diamond = [&](int cx, int cy, int r) {
    for (int d = -r; d <= r; ++d) {
      set(cx + d, cy + (r - std::abs(d)));
      set(cx + d, cy - (r - std::abs(d)));
    }
    pockets.push_back({cx, cy});
  };
  const auto circle = [&](int cx, int cy, double r) {
    for (int y = cy - r - 2; y <= cy + r + 2; ++y)
      for (int x = cx - r - 2; x <= cx + r + 2; ++x)
        if (std::abs(std::hypot(x - cx, y - cy) - r) < 0.5) set(x, y);
    pockets.push_back({cx, cy});
  };
  rectangle(10, 10, 60, 50);
  rectangle(20, 20, 40, 40);  // nested
  rectangle(61, 10, 90, 50);  // sharing no cell, touching the first one's wall
  diamond(150, 60, 40);
  diamond(150, 60, 12);  // nested
  diamond(60, 150, 25);
  diamond(86, 150, 1);  // a pocket of one cell: its walls touch the diamond above at a corner
  circle(170, 170, 45.3);
  circle(110, 200, 20.0);
  circle(200, 100, 10.7);
  Rng rng(18);
  std::vector<Vec2> dirs;
  std::vector<double> angles, out;
  FanScratch scratch;
  long hits = 0, fans = 0;
  for (const double yaw : {0.0, 0.6}) {
    const OccupancyGrid g(n, n, 0.05, Pose2{Vec2(-2.0, 1.0), yaw}, cells);
    const double c = std::cos(yaw), s = std::sin(yaw);
    const auto to_world = [&](double x, double y) {
      return Vec2(-2.0 + 0.05 * (c * x - s * y), 1.0 + 0.05 * (s * x + c * y));
    };
    for (int f = 0; f < 400; ++f) {
      double x = 0.0, y = 0.0;
      if (f % 4 == 3) {  // anywhere: mostly outside the outlines
        x = rng.uniform(0.0, n), y = rng.uniform(0.0, n);
      } else {
        const Pocket& p = pockets[static_cast<std::size_t>(f) % pockets.size()];
        x = p.cx + rng.uniform(-0.5, 1.5), y = p.cy + rng.uniform(-0.5, 1.5);
        if (f % 4 == 1) x = std::round(x), y = std::round(y);  // a cell corner
      }
      const Vec2 o = to_world(x, y);
      if (!(g.clearance(o) > 0.0)) continue;
      const double range = f % 3 == 0 ? 30.0 : (f % 3 == 1 ? 8.0 : 1.0);
      lidar(rng.uniform(-kPi, kPi), f % 2 == 0 ? kPi : 2.0 * kPi, 180, dirs, angles);
      out.assign(dirs.size(), -1.0);
      g.cast_fan(o, dirs, angles, range, out, scratch);
      ++fans;
      for (std::size_t k = 0; k < dirs.size(); ++k) {
        const double oracle = g.cast_ray_cell_by_cell(o, dirs[k], range);
        if (oracle < range) ++hits;
        ASSERT_EQ(bits(out[k]), bits(oracle))
            << "yaw " << yaw << " fan " << f << " beam " << k << " from cell (" << x << ", " << y
            << ") range " << range << ": fan " << out[k] << ", oracle " << oracle;
      }
    }
  }
  EXPECT_GT(fans, 700);
  EXPECT_GT(hits, fans * 180 / 2);
}

// From outside the grid (a robot that has driven off the map): `cast` clips each ray to the grid
// and starts its walk where the ray enters. Origins just outside a side, outside a corner, on the
// extension of a border line and on cell corners, at up to the beams' reach; 180-beam half-turn
// and full-turn fans and fans of axis-parallel beams; the cave walled all round (the border
// cells are hit from outside) and random grids whose border cells are partly occupied.
TEST(GridFanLongRange, MatchesTheCellByCellWalkFromOutsideTheGrid) {
  const bench::CaveMap cave = bench::make_cave_map();
  std::vector<std::pair<const OccupancyGrid*, const char*>> grids{{cave.grid.get(), "cave"}};
  std::vector<OccupancyGrid> random;
  Rng rng(17);
  for (int m = 0; m < 12; ++m) {
    const int w = 20 + static_cast<int>(rng.uniform(0.0, 150.0));
    const int h = 20 + static_cast<int>(rng.uniform(0.0, 150.0));
    std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * h);
    for (auto& c : cells) c = rng.uniform() < 0.02 ? 1 : 0;
    for (int x = 0; x < w; ++x) {  // border rows and columns, with gaps
      if (rng.uniform() < 0.5) cells[x] = 1;
      if (rng.uniform() < 0.5) cells[static_cast<std::size_t>(h - 1) * w + x] = 1;
    }
    for (int y = 0; y < h; ++y) {
      if (rng.uniform() < 0.5) cells[static_cast<std::size_t>(y) * w] = 1;
      if (rng.uniform() < 0.5) cells[static_cast<std::size_t>(y) * w + w - 1] = 1;
    }
    random.emplace_back(w, h, 0.05, Pose2{Vec2(-0.3, 0.8), m % 3 == 0 ? 0.7 : 0.0}, cells);
  }
  for (const OccupancyGrid& g : random) grids.emplace_back(&g, "random grid");

  std::vector<Vec2> dirs;
  std::vector<double> angles, out;
  FanScratch scratch;
  long hits = 0;
  for (const auto& [g, what] : grids) {
    const double res = g->resolution();
    const Pose2& go = g->origin();
    const double c = std::cos(go.theta), s = std::sin(go.theta);
    const auto to_world = [&](const Vec2& cell) {
      const Vec2 q = cell * res;
      return Vec2(go.position.x() + c * q.x() - s * q.y(), go.position.y() + s * q.x() + c * q.y());
    };
    const double w = g->width(), h = g->height();
    for (int f = 0; f < 200; ++f) {
      // How far outside (cells): just outside, a few cells, up to the reach of the range.
      const double range = f % 3 == 0 ? 3.5 : 8.0;
      const double far = f % 4 == 0 ? 1e-4 : rng.uniform(0.0, 1.2 * range / res);
      Vec2 cell;
      switch (f % 5) {
        case 0:
          cell = Vec2(-far, rng.uniform(0.0, h));
          break;  // left
        case 1:
          cell = Vec2(rng.uniform(0.0, w), h + far);
          break;  // above
        case 2:
          cell = Vec2(w + far, -far);
          break;  // a corner
        case 3:
          cell = Vec2(std::round(rng.uniform(0.0, w)), -far);
          break;  // a column line
        default:
          cell = Vec2(std::round(-far), std::round(rng.uniform(0.0, h)));  // a cell corner
      }
      const Vec2 p = to_world(cell);
      if (f % 6 == 5) {
        // Eight beams along the grid's axes and diagonals.
        dirs.clear();
        angles.clear();
        for (int k = 0; k < 8; ++k) {
          const double a = wrap_angle(go.theta + k * 0.25 * kPi);
          angles.push_back(a);
          dirs.emplace_back(std::cos(a), std::sin(a));
        }
      } else {
        lidar(rng.uniform(-kPi, kPi), f % 2 == 0 ? kPi : 2.0 * kPi, 180, dirs, angles);
      }
      out.assign(dirs.size(), -1.0);
      g->cast_fan(p, dirs, angles, range, out, scratch);
      for (std::size_t k = 0; k < dirs.size(); ++k) {
        const double oracle = g->cast_ray_cell_by_cell(p, dirs[k], range);
        if (oracle < range) ++hits;
        ASSERT_EQ(bits(out[k]), bits(oracle))
            << what << " fan " << f << " beam " << k << " from cell (" << cell.x() << ", "
            << cell.y() << ") angle " << angles[k] << " range " << range << ": fan " << out[k]
            << ", oracle " << oracle;
      }
    }
  }
  // Most fans reach the grid: the comparison is about hits, not only misses.
  EXPECT_GT(hits, 13 * 200 * 180 / 8);
}

}  // namespace
}  // namespace floornav
