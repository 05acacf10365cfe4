// OccupancyGrid::cast_ray (free-space jumps) against cast_ray_cell_by_cell, bit for bit, on
// random grids and on the AWS warehouse map.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/io/ros_map.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "support/bits.hpp"

namespace floornav {
namespace {

using test::bits;

constexpr double kInf = std::numeric_limits<double>::infinity();

void expect_grid_rays_match(const OccupancyGrid& g, Rng& rng, int rays, const char* what) {
  Vec2 lo, hi;
  g.world_extent(&lo, &hi);
  const Vec2 span = hi - lo;
  const double res = g.resolution();
  for (int k = 0; k < rays; ++k) {
    Vec2 p(lo.x() + span.x() * rng.uniform(-0.2, 1.2), lo.y() + span.y() * rng.uniform(-0.2, 1.2));
    if (k % 5 == 1) p = (p / res).array().round().matrix() * res;  // on cell corners (yaw 0)
    double a = rng.uniform(-kPi, kPi);
    if (k % 7 == 2) a = std::round(a / (0.25 * kPi)) * 0.25 * kPi;  // axis and diagonal rays
    const Vec2 dir(std::cos(a), std::sin(a));
    const int pick = k % 4;
    const double range = pick == 0 ? kInf : (pick == 1 ? 3.5 : rng.uniform(0.0, span.norm() * 1.5));
    const double fast = g.cast_ray(p, dir, range);
    const double slow = g.cast_ray_cell_by_cell(p, dir, range);
    ASSERT_EQ(bits(fast), bits(slow)) << what << " ray " << k << " from (" << p.x() << ", " << p.y()
                                      << ") angle " << a << " range " << range;
  }
}

TEST(GridCast, JumpsMatchCellByCellOnRandomGrids) {
  Rng rng(42);
  for (int n = 0; n < 40; ++n) {
    const int w = 1 + static_cast<int>(rng.uniform(0.0, 300.0));
    const int h = 1 + static_cast<int>(rng.uniform(0.0, 300.0));
    const double density = std::pow(10.0, rng.uniform(-4.0, -0.5));
    std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * h);
    for (auto& c : cells) c = rng.uniform() < density ? 1 : 0;
    const double yaw = n % 3 == 0 ? rng.uniform(-kPi, kPi) : 0.0;
    const double res = n % 2 == 0 ? 0.05 : 0.1;
    const OccupancyGrid g(w, h, res, Pose2{Vec2(-1.0, -2.0), yaw}, cells);
    ASSERT_NO_FATAL_FAILURE(expect_grid_rays_match(g, rng, 3000, "random grid"));
  }
}

TEST(GridCast, JumpsMatchCellByCellOnTheAwsWarehouse) {
  const auto map = std::filesystem::path(FLOORNAV_TEST_DATA_DIR) / "maps" /
                   "aws-robomaker-small-warehouse" / "005" / "map.yaml";
  const OccupancyGrid g = load_ros_map(map);
  Rng rng(9);
  ASSERT_NO_FATAL_FAILURE(expect_grid_rays_match(g, rng, 300000, "AWS 005"));
  // And from the free points a robot would be at, with a lidar's fan of rays.
  Vec2 lo, hi;
  g.world_extent(&lo, &hi);
  int origins = 0;
  while (origins < 300) {
    const Vec2 p(rng.uniform(lo.x(), hi.x()), rng.uniform(lo.y(), hi.y()));
    if (!(g.clearance(p) > 0.1)) continue;
    ++origins;
    for (int k = 0; k < 360; ++k) {
      const double a = wrap_angle(2.0 * kPi * k / 360.0 + 0.1 * origins);
      const Vec2 dir(std::cos(a), std::sin(a));
      ASSERT_EQ(bits(g.cast_ray(p, dir, 3.5)), bits(g.cast_ray_cell_by_cell(p, dir, 3.5)));
    }
  }
}

}  // namespace
}  // namespace floornav
