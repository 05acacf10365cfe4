// OccupancyGrid::cast_fan (and World::cast_fan over a grid) against OccupancyGrid::cast_ray and
// cast_ray_cell_by_cell, bit for bit, on random grids and on the AWS warehouse map.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <utility>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/fan_cone.hpp"
#include "floornav/geometry/fan_layout.hpp"
#include "floornav/io/ros_map.hpp"
#include "floornav/world/fan_index.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"
#include "support/bits.hpp"

namespace floornav {
namespace {

using test::bits;

constexpr double kInf = std::numeric_limits<double>::infinity();

// A lidar's beams: angle first + k * 2 pi / n, wrapped as sensors wrap them. Beams within 1e-12
// rad of an axis or a diagonal get the exact axis or diagonal direction (angles within 1e-9 of
// the direction's are what cast_fan asks for).
void make_fan(double first, int n, std::vector<Vec2>& dirs, std::vector<double>& angles) {
  dirs.resize(n);
  angles.resize(n);
  const double s = std::sqrt(0.5);
  for (int k = 0; k < n; ++k) {
    const double a = wrap_angle(first + 2.0 * kPi * k / n);
    angles[k] = a;
    dirs[k] = Vec2(std::cos(a), std::sin(a));
    const double q = a / (0.25 * kPi);
    if (std::abs(q - std::round(q)) < 1e-12) {
      const int o = (static_cast<int>(std::round(q)) % 8 + 8) % 8;
      const double ex[8] = {1.0, s, 0.0, -s, -1.0, -s, 0.0, s};
      const double ey[8] = {0.0, s, 1.0, s, 0.0, -s, -1.0, -s};
      dirs[k] = Vec2(ex[o], ey[o]);
    }
  }
}

// Fans from `fans` origins on `g`: every beam bit for bit cast_ray (and, for every 8th fan,
// cast_ray_cell_by_cell). Adds the number of rays compared to `rays`.
void expect_grid_fans_match(const OccupancyGrid& g, Rng& rng, int fans, bool near_free,
                            const char* what, long& rays) {
  Vec2 lo, hi;
  g.world_extent(&lo, &hi);
  const Vec2 span = hi - lo;
  const double res = g.resolution();
  const Pose2& go = g.origin();
  const double c = std::cos(go.theta), s = std::sin(go.theta);
  std::vector<Vec2> dirs;
  std::vector<double> angles, out;
  WorldDesc desc;
  desc.grid = std::make_shared<const OccupancyGrid>(g);
  const World world(std::move(desc));
  for (int f = 0; f < fans; ++f) {
    Vec2 p(lo.x() + span.x() * rng.uniform(-0.1, 1.1), lo.y() + span.y() * rng.uniform(-0.1, 1.1));
    if (near_free && f % 4 != 3) {
      do {
        p = Vec2(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()));
      } while (!(g.clearance(p) > 0.05));
    }
    // On a cell corner or a cell edge of the grid frame (any yaw), sometimes.
    const int place = f % 6;
    if (place == 1 || place == 2) {
      const Vec2 d = p - go.position;
      Vec2 q(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
      q /= res;
      q.x() = std::round(q.x());
      if (place == 1) q.y() = std::round(q.y());
      q *= res;
      p = go.position + Vec2(c * q.x() - s * q.y(), s * q.x() + c * q.y());
    }
    const int pick_n = f % 5;
    const int n = pick_n == 0 ? 180 : (pick_n == 1 ? 64 : (pick_n == 2 ? 720 : 360));
    double first = rng.uniform(-kPi, kPi);
    if (f % 3 == 0) first = go.theta + std::round(first / (0.25 * kPi)) * 0.25 * kPi;
    make_fan(first, n, dirs, angles);
    const int pick_r = f % 7;
    const double range =
        pick_r == 0 ? 3.5 : (pick_r == 1 ? 0.0 : (pick_r == 2 ? 1e9 : rng.uniform(0.0, 8.0)));
    out.assign(n, -1.0);
    // One scratch for all fans of all grids (sizes change from fan to fan); the World below
    // casts with scratch of its own.
    static FanScratch scratch;
    g.cast_fan(p, dirs, angles, range, out, scratch);
    for (int k = 0; k < n; ++k) {
      const double want = g.cast_ray(p, dirs[k], range);
      ASSERT_EQ(bits(out[k]), bits(want))
          << what << " fan " << f << " beam " << k << " from (" << p.x() << ", " << p.y()
          << ") angle " << angles[k] << " range " << range << ": " << out[k] << " vs " << want;
      if (f % 8 == 0) {
        ASSERT_EQ(bits(out[k]), bits(g.cast_ray_cell_by_cell(p, dirs[k], range)));
      }
    }
    rays += n;
    if (f % 10 == 0) {
      world.cast_fan(p, dirs, angles, range, out);
      for (int k = 0; k < n; ++k)
        ASSERT_EQ(bits(out[k]), bits(world.cast_ray(p, dirs[k], range))) << what << " world fan";
    }
  }
}

// The fans' floor without libm: std::floor's values (a zero may differ in sign, which compares
// equal), at integers, halves, just beside integers, past 2^52, at infinities and NaN, and on
// random values of every magnitude.
TEST(FanLayout, FloorByTruncationIsLibms) {
  using fan_detail::floor_by_truncation;
  std::vector<double> xs{0.0,
                         -0.0,
                         0.5,
                         -0.5,
                         1.0,
                         -1.0,
                         2.5,
                         -2.5,
                         1e-300,
                         -1e-300,
                         0x1p52,
                         -0x1p52,
                         0x1p52 + 1,
                         0x1p60,
                         1e300,
                         -1e300,
                         kInf,
                         -kInf,
                         std::nextafter(3.0, 0.0),
                         std::nextafter(-3.0, 0.0),
                         std::nextafter(0x1p52, 0.0),
                         -std::nextafter(0x1p52, 0.0)};
  Rng rng(3);
  for (int i = 0; i < 100000; ++i) xs.push_back(std::ldexp(rng.uniform(-1.0, 1.0), i % 70 - 10));
  for (const double x : xs) {
    EXPECT_EQ(floor_by_truncation(x), std::floor(x)) << x;
  }
  EXPECT_TRUE(std::isnan(floor_by_truncation(std::nan(""))));
}

// even_fan takes evenly spaced angles, wrapped or not, and refuses one beam off its place by
// more than the tolerance, or NaN, wherever it is after the two that set the step (the check
// runs two beams at a time, then the last one alone): every position of fans of odd and even
// sizes.
TEST(FanLayout, EvenFanRefusesAnyBeamOffItsPlace) {
  for (const int n : {2, 3, 16, 17, 180, 181}) {
    for (const double first : {-3.1, 0.0, 2.9}) {
      const double step = 3.0 / (n - 1);
      std::vector<double> angles(static_cast<std::size_t>(n));
      for (int k = 0; k < n; ++k)
        angles[static_cast<std::size_t>(k)] = wrap_angle(first + k * step);
      const auto fan = fan_detail::even_fan(angles);
      ASSERT_TRUE(fan.has_value()) << n << " " << first;
      EXPECT_EQ(fan->n, n);
      EXPECT_NEAR(fan->step, step, 1e-12);
      for (int k = 2; k < n; ++k) {  // beam 1 sets the step
        for (const double off : {0.5e-9, -0.5e-9, 2e-9, -2e-9, std::nan("")}) {
          std::vector<double> moved = angles;
          moved[static_cast<std::size_t>(k)] += off;
          const bool within = std::abs(off) < 1e-9;  // false for NaN
          EXPECT_EQ(fan_detail::even_fan(moved).has_value(), within)
              << "n " << n << " first " << first << " beam " << k << " moved by " << off;
        }
      }
    }
  }
}

// The diamond angle grows with the angle: worked at the axes and diagonals, and in order over a
// fine sweep of directions of every length.
TEST(FanCone, DiamondAngleGrowsWithTheAngle) {
  using fan_detail::diamond_angle;
  EXPECT_EQ(diamond_angle(1.0, 0.0), 0.0);
  EXPECT_EQ(diamond_angle(2.0, 2.0), 0.5);
  EXPECT_EQ(diamond_angle(0.0, 3.0), 1.0);
  EXPECT_EQ(diamond_angle(-1.0, 1.0), 1.5);
  EXPECT_EQ(diamond_angle(-1.0, 0.0), 2.0);
  EXPECT_EQ(diamond_angle(-1.0, -1.0), 2.5);
  EXPECT_EQ(diamond_angle(0.0, -1.0), 3.0);
  EXPECT_EQ(diamond_angle(1.0, -1.0), 3.5);
  EXPECT_EQ(diamond_angle(-0.0, 1.0), 1.0);  // a negative zero x is not left of the origin
  double last = -1.0;
  for (int i = 0; i < 100000; ++i) {
    const double a = 2.0 * kPi * i / 100000, len = std::ldexp(1.0, i % 40 - 20);
    const double p = diamond_angle(len * std::cos(a), len * std::sin(a));
    EXPECT_GE(p, last) << a;
    EXPECT_LT(p, 4.0) << a;
    last = p;
  }
  // Each bin's bounds hold the angles of its diamond angles.
  const auto& bounds = fan_detail::diamond_bounds();
  EXPECT_EQ(bounds.front(), 0.0f);
  EXPECT_NEAR(bounds[fan_detail::kDiamondBins / 4], 0.5 * kPi, 1e-6);
  EXPECT_NEAR(bounds.back(), 2.0 * kPi, 1e-6);
}

// A fan of 2 to 401 beams, from any start, a full turn less a step wide every third trial and
// otherwise 0.01 to 2 pi - 0.1 rad.
fan_detail::FanLayout random_fan(Rng& rng, int trial) {
  const int n = 2 + static_cast<int>(rng.uniform(0.0, 400.0));
  const double width =
      trial % 3 == 0 ? 2.0 * kPi * (n - 1) / n : rng.uniform(0.01, 2.0 * kPi - 0.1);
  fan_detail::FanLayout fan;
  fan.first = rng.uniform(-10.0, 10.0);
  fan.step = width / (n - 1);
  fan.inv_step = 1.0 / fan.step;
  fan.n = n;
  return fan;
}

// FanCone::for_beams against atan2: every beam whose angle lies in the cone (widened by the
// margin) is called, for fans of every width and start, frames turned every way and cones across
// angle 0 of either frame; and not many more (a bin's width beyond each edge).
TEST(FanCone, CallsEveryBeamInTheConeAndFewOthers) {
  Rng rng(31);
  long extra = 0, inside = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const fan_detail::FanLayout fan = random_fan(rng, trial);
    const int n = fan.n;
    const double yaw = trial % 5 == 0 ? 0.0 : rng.uniform(-7.0, 7.0);
    const fan_detail::FanCone cone(fan, yaw);
    const double a0 = rng.uniform(-kPi, kPi), span = rng.uniform(0.0, kPi - 1e-3);
    const double l0 = rng.uniform(0.1, 100.0), l1 = rng.uniform(0.1, 100.0);
    std::vector<int> calls(static_cast<std::size_t>(n), 0);
    cone.for_beams(l0 * std::cos(a0), l0 * std::sin(a0), l1 * std::cos(a0 + span),
                   l1 * std::sin(a0 + span), [&](int k) {
                     ASSERT_GE(k, 0);
                     ASSERT_LT(k, n);
                     ++calls[static_cast<std::size_t>(k)];
                   });
    for (int k = 0; k < n; ++k) {
      // Beam k's angle in the vectors' frame, from the cone's first edge, in [0, 2 pi).
      const double a = std::remainder(fan.first + k * fan.step - yaw - a0, 2.0 * kPi);
      const double from = a < 0.0 ? a + 2.0 * kPi : a;
      const bool in = from <= span + fan_detail::kFanMargin * 0.99 ||
                      from >= 2.0 * kPi - fan_detail::kFanMargin * 0.99;
      const bool near = from <= span + 0.005 || from >= 2.0 * kPi - 0.005;
      if (in) {
        ++inside;
        EXPECT_EQ(calls[static_cast<std::size_t>(k)], 1) << "trial " << trial << " beam " << k;
      } else {
        EXPECT_LE(calls[static_cast<std::size_t>(k)], 1) << "trial " << trial << " beam " << k;
        if (calls[static_cast<std::size_t>(k)] != 0) {
          ++extra;
          EXPECT_TRUE(near) << "trial " << trial << " beam " << k << " at " << from;
        }
      }
    }
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(inside, 100000);
  EXPECT_LT(extra, inside / 20);
}

// FanCone::for_spans_about gives the beams for_beams_about calls, each once, as at most two
// intervals: for cones across beam 0 (a turn later), fans of every width, half-widths up to pi.
TEST(FanCone, SpansAboutAreTheBeamsForBeamsAboutCalls) {
  Rng rng(37);
  int wrapped = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const fan_detail::FanLayout fan = random_fan(rng, trial);
    const int n = fan.n;
    const fan_detail::FanCone cone(fan, trial % 5 == 0 ? 0.0 : rng.uniform(-7.0, 7.0));
    const double a = rng.uniform(-kPi, kPi), l = rng.uniform(0.1, 100.0);
    const double half = trial % 7 == 0 ? kPi : rng.uniform(0.0, 1.0);
    const double x = l * std::cos(a), y = l * std::sin(a);
    std::vector<int> calls(static_cast<std::size_t>(n), 0), spans(calls);
    cone.for_beams_about(x, y, half, [&](int k) { ++calls[static_cast<std::size_t>(k)]; });
    int count = 0;
    cone.for_spans_about(x, y, half, [&](int k0, int k1) {
      ASSERT_LE(0, k0);
      ASSERT_LE(k0, k1);
      ASSERT_LT(k1, n);
      for (int k = k0; k <= k1; ++k) ++spans[static_cast<std::size_t>(k)];
      wrapped += ++count == 2;
    });
    ASSERT_EQ(spans, calls) << "trial " << trial;
  }
  EXPECT_GT(wrapped, 100);  // cones across beam 0 were among them
}

TEST(GridFan, MatchesCastRayOnRandomGrids) {
  Rng rng(7);
  long rays = 0;
  for (int n = 0; n < 60; ++n) {
    const int w = 1 + static_cast<int>(rng.uniform(0.0, 200.0));
    const int h = 1 + static_cast<int>(rng.uniform(0.0, 200.0));
    const double density = std::pow(10.0, rng.uniform(-3.0, -0.3));
    std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * h);
    for (auto& c : cells) c = rng.uniform() < density ? 1 : 0;
    if (n % 4 == 1) {
      // Walls: runs of occupied cells along rows and columns.
      for (int r = 0; r < 10; ++r) {
        const int x0 = static_cast<int>(rng.uniform(0.0, w)),
                  y0 = static_cast<int>(rng.uniform(0.0, h));
        const int len = static_cast<int>(rng.uniform(1.0, 60.0));
        for (int i = 0; i < len; ++i) {
          const int x = r % 2 == 0 ? x0 + i : x0, y = r % 2 == 0 ? y0 : y0 + i;
          if (x < w && y < h) cells[static_cast<std::size_t>(y) * w + x] = 1;
        }
      }
    }
    if (n % 4 == 3) {
      // Walls at any angle: staircases of cells, whose faces are runs of one cell on two sides
      // (the cave's walls are mostly such).
      for (int r = 0; r < 10; ++r) {
        const double x0 = rng.uniform(0.0, w), y0 = rng.uniform(0.0, h);
        const double a = rng.uniform(-kPi, kPi), len = rng.uniform(1.0, 80.0);
        for (double t = 0.0; t <= len; t += 0.25) {
          const int x = static_cast<int>(x0 + t * std::cos(a));
          const int y = static_cast<int>(y0 + t * std::sin(a));
          if (x >= 0 && y >= 0 && x < w && y < h) cells[static_cast<std::size_t>(y) * w + x] = 1;
        }
      }
    }
    const double yaw = n % 3 == 0 ? rng.uniform(-kPi, kPi) : (n % 3 == 1 ? 0.5 * kPi : 0.0);
    const double res = n % 2 == 0 ? 0.05 : 0.1;
    const OccupancyGrid g(w, h, res, Pose2{Vec2(-1.0, -2.0), yaw}, cells);
    ASSERT_NO_FATAL_FAILURE(expect_grid_fans_match(g, rng, 60, n % 2 == 0, "random grid", rays));
  }
  EXPECT_GT(rays, 1000000);
}

// Which one-cell runs the fan may leave out: a cell's left and right faces, each a run of one cell,
// are covered by the row runs of its bottom and top faces that end at it; a run of one cell covers
// one of another side only when it comes later (bottom and top cover no left or right face
// back), and a longer run covers whatever ends at its end cells.
TEST(GridFan, KeepsWhichOneCellRunsAnotherRunCovers) {
  const auto counts = [](int w, int h, std::initializer_list<std::pair<int, int>> occupied) {
    std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * h, 0);
    for (const auto& [x, y] : occupied) cells[static_cast<std::size_t>(y) * w + x] = 1;
    return OccupancyGrid(w, h, 0.1, Pose2{}, cells).fan_index().run_counts();
  };
  // One cell: four runs of one cell; its left and right faces covered, its bottom and top not.
  auto c = counts(5, 5, {{2, 2}});
  EXPECT_EQ(c.runs, 4u);
  EXPECT_EQ(c.covered, 2u);
  // Two cells in a row: the row's bottom and top runs (two cells) cover the end faces.
  c = counts(6, 5, {{2, 2}, {3, 2}});
  EXPECT_EQ(c.runs, 4u);
  EXPECT_EQ(c.covered, 2u);
  // Two cells in a column: its left and right runs (two cells) cover the bottom and top faces.
  c = counts(5, 6, {{2, 2}, {2, 3}});
  EXPECT_EQ(c.runs, 4u);
  EXPECT_EQ(c.covered, 2u);
  // A staircase of three cells touching at corners: each cell is alone among free cells.
  c = counts(7, 7, {{1, 1}, {2, 2}, {3, 3}});
  EXPECT_EQ(c.runs, 12u);
  EXPECT_EQ(c.covered, 6u);
  // An H: two columns of three cells joined by a cell between their middles. Twelve runs: each
  // column's outer side (three cells), the inner sides' end cells, the bottom and top faces of
  // the columns' end cells and of the middle cell. The columns' single faces are all covered;
  // the middle cell's bottom and top faces are not (no run of its column ends at it).
  c = counts(7, 5, {{2, 1}, {2, 2}, {2, 3}, {3, 2}, {4, 1}, {4, 2}, {4, 3}});
  EXPECT_EQ(c.runs, 12u);
  EXPECT_EQ(c.covered, 8u);
}

// Beams the fan does not take (directions that are not unit vectors) are cast ray by ray, among
// beams it takes; a range of -0 reads -0 where nothing is hit, as cast_ray does.
TEST(GridFan, CastsBeamsWithOtherDirectionsRayByRay) {
  std::vector<std::uint8_t> cells(60 * 40, 0);
  for (int y = 0; y < 40; ++y) cells[static_cast<std::size_t>(y) * 60 + 45] = 1;
  for (int x = 0; x < 60; ++x) cells[static_cast<std::size_t>(35) * 60 + x] = 1;
  const OccupancyGrid g(60, 40, 0.1, Pose2{Vec2(0.0, 0.0), 0.0}, cells);
  const Vec2 o(1.23, 0.71);
  std::vector<Vec2> dirs;
  std::vector<double> angles;
  make_fan(-0.3, 90, dirs, angles);
  dirs[7] *= 2.0;  // not unit: cast ray by ray
  dirs[50] *= 0.5;
  for (const double range : {10.0, -0.0, 0.0}) {
    std::vector<double> out(dirs.size(), -1.0);
    g.cast_fan(o, dirs, angles, range, out);
    for (std::size_t k = 0; k < dirs.size(); ++k)
      EXPECT_EQ(bits(out[k]), bits(g.cast_ray(o, dirs[k], range)))
          << "range " << range << " beam " << k;
  }
  std::vector<double> out(dirs.size());
  g.cast_fan(o, dirs, angles, 10.0, out);
  EXPECT_NE(out[7], g.cast_ray(o, dirs[7] / 2.0, 10.0));  // a doubled direction halves t
}

TEST(GridFan, MatchesCastRayOnTheAwsWarehouse) {
  const auto map = std::filesystem::path(FLOORNAV_TEST_DATA_DIR) / "maps" /
                   "aws-robomaker-small-warehouse" / "005" / "map.yaml";
  const OccupancyGrid g = load_ros_map(map);
  Rng rng(11);
  long rays = 0;
  ASSERT_NO_FATAL_FAILURE(expect_grid_fans_match(g, rng, 1500, true, "AWS 005", rays));
  EXPECT_GT(rays, 400000);
}

}  // namespace
}  // namespace floornav
