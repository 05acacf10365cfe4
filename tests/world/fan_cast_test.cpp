// World::cast_fan against World::cast_ray per ray, bit for bit, and sense_ranges' fan path
// against casting sensor by sensor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sensing/sensor_fans.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"
#include "support/bits.hpp"

namespace floornav {
namespace {

using test::bits;

/// A random walled floor: star-shaped polygons (some sharing vertices' rows and columns, so that
/// rays graze them), circles and points, optionally over an occupancy grid.
struct RandomWorld {
  std::shared_ptr<const OccupancyGrid> grid;
  std::unique_ptr<World> world;
};

RandomWorld random_world(Rng& rng, bool with_grid) {
  RandomWorld rw;
  WorldDesc d;
  const double side = rng.uniform(3.0, 25.0);
  if (rng.uniform() < 0.8) d.bounds = Box2{Vec2(0.0, 0.0), Vec2(side, side)};
  const int polygons = static_cast<int>(rng.uniform(0.0, 40.0));
  for (int p = 0; p < polygons; ++p) {
    const Vec2 c(rng.uniform(0.0, side), rng.uniform(0.0, side));
    const double r = rng.uniform(0.05, 1.5);
    const int n = 3 + static_cast<int>(rng.uniform(0.0, 6.0));
    const bool grid_aligned = rng.uniform() < 0.3;  // axis-aligned boxes: many exact ties
    std::vector<Vec2> poly;
    if (grid_aligned) {
      const double x0 = std::round(c.x()), y0 = std::round(c.y());
      const double w = std::round(rng.uniform(1.0, 3.0)) * 0.5, h = std::round(r + 0.5) * 0.5;
      poly = {{x0, y0}, {x0 + w, y0}, {x0 + w, y0 + h}, {x0, y0 + h}};
    } else {
      for (int i = 0; i < n; ++i) {
        const double a = 2.0 * kPi * (i + rng.uniform(-0.3, 0.3)) / n;
        const double rr = r * rng.uniform(0.4, 1.0);
        poly.emplace_back(c.x() + rr * std::cos(a), c.y() + rr * std::sin(a));
      }
    }
    // Either winding: the casts skip the edges seen from their solid side, which it decides.
    if (rng.uniform() < 0.5) std::reverse(poly.begin(), poly.end());
    d.polygons.push_back(poly);
  }
  const int circles = static_cast<int>(rng.uniform(0.0, 15.0));
  for (int i = 0; i < circles; ++i) {
    const double radius = rng.uniform() < 0.2 ? 0.0 : rng.uniform(0.02, 1.0);
    d.circles.push_back({Vec2(rng.uniform(0.0, side), rng.uniform(0.0, side)), radius});
  }
  if (with_grid) {
    const int w = 20 + static_cast<int>(rng.uniform(0.0, 60.0));
    const int h = 20 + static_cast<int>(rng.uniform(0.0, 60.0));
    std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * h);
    for (auto& c : cells) c = rng.uniform() < 0.02 ? 1 : 0;
    const double res = side / std::max(w, h);
    const double yaw = rng.uniform() < 0.5 ? 0.0 : rng.uniform(-kPi, kPi);
    rw.grid = std::make_shared<const OccupancyGrid>(w, h, res, Pose2{Vec2(0.1, 0.2), yaw}, cells);
    d.grid = rw.grid;
  }
  rw.world = std::make_unique<World>(std::move(d));
  return rw;
}

/// Origins that stress the fan: random points (free or inside obstacles), points a hair off an
/// edge or a circle, vertices themselves, and points outside the bounds.
std::vector<Vec2> tricky_origins(const World& w, Rng& rng) {
  std::vector<Vec2> out;
  const Box2 e = w.extent();
  const Vec2 size = e.size().cwiseMax(Vec2(1.0, 1.0));
  for (int i = 0; i < 12; ++i)
    out.emplace_back(e.min.x() + size.x() * rng.uniform(-0.1, 1.1),
                     e.min.y() + size.y() * rng.uniform(-0.1, 1.1));
  const auto segs = w.segments();
  for (int i = 0; i < 12 && !segs.empty(); ++i) {
    const Segment& s = segs[static_cast<std::size_t>(rng.uniform(0.0, segs.size() - 0.5))];
    const Vec2 e2 = s.b - s.a;
    const Vec2 normal = Vec2(-e2.y(), e2.x()).normalized();
    const double off = std::pow(10.0, rng.uniform(-12.0, -2.0)) * (rng.uniform() < 0.5 ? -1 : 1);
    if (i % 4 == 0) {
      out.push_back(s.a);  // on a vertex
    } else {
      out.push_back(s.a + rng.uniform(0.0, 1.0) * e2 + off * normal);
    }
  }
  for (const Circle& c : w.circles()) {
    const double a = rng.uniform(-kPi, kPi);
    out.push_back(c.center + (c.radius + std::pow(10.0, rng.uniform(-12.0, -3.0))) *
                                 Vec2(std::cos(a), std::sin(a)));
  }
  return out;
}

/// An even fan as a lidar makes it: beam k at wrap(first + k * step).
void make_fan(double first, double fov, int n, std::vector<Vec2>& dirs,
              std::vector<double>& angles) {
  const bool full = fov >= 2.0 * kPi - 1e-9;
  const double step = fov / (full ? n : n - 1);
  dirs.clear();
  angles.clear();
  for (int k = 0; k < n; ++k) {
    const double a = wrap_angle(first + k * step);
    angles.push_back(a);
    dirs.emplace_back(std::cos(a), std::sin(a));
  }
}

/// One scratch for every fan of these tests, whatever their size and world: what it keeps from
/// one fan (marks of another world's obstacles, longer buffers) must not change the next.
FanScratch& shared_scratch() {
  static FanScratch scratch;
  return scratch;
}

/// Fails on the first beam that differs from cast_ray.
void expect_fan_matches(const World& w, const Vec2& o, const std::vector<Vec2>& dirs,
                        const std::vector<double>& angles, double max_range, bool from_free) {
  std::vector<double> out(dirs.size(), -1.0);
  if (from_free) {
    w.cast_fan_from_free(o, dirs, angles, max_range, out, shared_scratch());
  } else {
    w.cast_fan(o, dirs, angles, max_range, out, shared_scratch());
  }
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    const double ref =
        from_free ? w.cast_ray_from_free(o, dirs[k], max_range) : w.cast_ray(o, dirs[k], max_range);
    ASSERT_EQ(bits(out[k]), bits(ref))
        << "beam " << k << " of " << dirs.size() << " from (" << o.x() << ", " << o.y()
        << ") angle " << angles[k] << " range " << max_range << ": fan " << out[k] << ", cast_ray "
        << ref;
  }
}

TEST(FanCast, MatchesCastRayBitForBitOnRandomWorlds) {
  Rng rng(20261123);
  std::vector<Vec2> dirs;
  std::vector<double> angles;
  int fans = 0;
  for (int world_no = 0; world_no < 200; ++world_no) {
    const RandomWorld rw = random_world(rng, world_no % 4 == 3);
    const World& w = *rw.world;
    for (const Vec2& o : tricky_origins(w, rng)) {
      const int sizes[] = {2, 16, 180, 360, 720};
      const int n = sizes[static_cast<int>(rng.uniform(0.0, 4.999))];
      const double fov = rng.uniform() < 0.7 ? 2.0 * kPi : rng.uniform(0.1, 6.2);
      const double range = rng.uniform() < 0.1 ? rng.uniform(30.0, 60.0) : rng.uniform(0.1, 6.0);
      make_fan(rng.uniform(-kPi, kPi), fov, n, dirs, angles);
      ASSERT_NO_FATAL_FAILURE(expect_fan_matches(w, o, dirs, angles, range, false));
      if (!w.is_inside_obstacle(o) && w.clearance(o) > 0.0) {
        ASSERT_NO_FATAL_FAILURE(expect_fan_matches(w, o, dirs, angles, range, true));
      }
      ++fans;
      // Beam 0 straight at a vertex within range: the ray grazes it.
      const auto segs = w.segments();
      if (!segs.empty()) {
        const Vec2 v = segs[static_cast<std::size_t>(rng.uniform(0.0, segs.size() - 0.5))].b;
        if (v != o) {
          make_fan(std::atan2(v.y() - o.y(), v.x() - o.x()), 2.0 * kPi, 180, dirs, angles);
          ASSERT_NO_FATAL_FAILURE(expect_fan_matches(w, o, dirs, angles, 30.0, false));
          ++fans;
        }
      }
    }
  }
  EXPECT_GT(fans, 2000);
}

TEST(FanCast, AxisAlignedBeamsAlongGridAlignedWalls) {
  // Origins on integer coordinates and beams every 90 degrees / 8: rays run exactly along the
  // walls of axis-aligned boxes and through their corners.
  WorldDesc d;
  d.bounds = Box2{Vec2(0.0, 0.0), Vec2(10.0, 10.0)};
  for (int i = 1; i < 9; i += 2)
    for (int j = 1; j < 9; j += 2)
      d.polygons.push_back(
          {{1.0 * i, 1.0 * j}, {i + 1.0, 1.0 * j}, {i + 1.0, j + 1.0}, {1.0 * i, j + 1.0}});
  const World w(std::move(d));
  std::vector<Vec2> dirs;
  std::vector<double> angles;
  for (int x = 0; x <= 10; ++x)
    for (int y = 0; y <= 10; ++y) {
      make_fan(0.0, 2.0 * kPi, 32, dirs, angles);
      ASSERT_NO_FATAL_FAILURE(expect_fan_matches(w, Vec2(x, y), dirs, angles, 20.0, false));
      ASSERT_NO_FATAL_FAILURE(
          expect_fan_matches(w, Vec2(x + 0.5, y + 1e-13), dirs, angles, 4.0, false));
    }
}

// cast_fan_from_free is cast_ray_from_free, min(max_range, the grid's cast_ray), to the bit: the
// minimum is left out for a positive range (it changes nothing there) and taken for 0 and -0; for
// -0 it turns the grid's hit at +0 (an origin on the face of an occupied cell) into -0.
TEST(FanCast, FromFreeOnAGridTakesTheRangeAsCastRayFromFreeDoes) {
  Rng rng(20261201);
  std::vector<Vec2> dirs;
  std::vector<double> angles;
  for (int world_no = 0; world_no < 40; ++world_no) {
    const int w = 12, h = 10;
    std::vector<std::uint8_t> cells(static_cast<std::size_t>(w) * h);
    for (auto& c : cells) c = rng.uniform() < 0.15 ? 1 : 0;
    cells[static_cast<std::size_t>(h / 2) * w + w / 2] = 0;      // the origin's cell, free
    cells[static_cast<std::size_t>(h / 2) * w + w / 2 + 1] = 1;  // and rock to its right
    const double res = 0.25;
    const auto grid = std::make_shared<const OccupancyGrid>(w, h, res, Pose2{}, cells);
    WorldDesc d;
    d.grid = grid;
    if (world_no % 2 == 1) d.circles.push_back({Vec2(0.4, 0.3), 0.1});  // the other branch
    const World world(std::move(d));
    // On the rock's face (a hit at +0 for the beams into it), and inside the free cell.
    const Vec2 on_face((w / 2 + 1) * res, (h / 2 + 0.5) * res);
    const Vec2 inside((w / 2 + rng.uniform(0.1, 0.9)) * res, (h / 2 + rng.uniform(0.1, 0.9)) * res);
    for (const Vec2& o : {on_face, inside}) {
      for (const double range : {2.5, 1e-310, 0.0, -0.0, std::numeric_limits<double>::infinity()}) {
        make_fan(rng.uniform(-kPi, kPi), 2.0 * kPi, 90, dirs, angles);
        ASSERT_NO_FATAL_FAILURE(expect_fan_matches(world, o, dirs, angles, range, true))
            << "world " << world_no << " range " << range;
      }
    }
  }
}

TEST(FanCast, UnevenAnglesFallBackToRayByRay) {
  Rng rng(5);
  const RandomWorld rw = random_world(rng, false);
  std::vector<Vec2> dirs;
  std::vector<double> angles;
  for (int k = 0; k < 50; ++k) {
    const double a = rng.uniform(-kPi, kPi);
    angles.push_back(a);
    dirs.emplace_back(std::cos(a), std::sin(a));
  }
  const Vec2 o = rw.world->extent().min + 0.5 * rw.world->extent().size();
  ASSERT_NO_FATAL_FAILURE(expect_fan_matches(*rw.world, o, dirs, angles, 5.0, false));
  // Clockwise fans too.
  make_fan(0.3, 2.0 * kPi, 90, dirs, angles);
  std::reverse(dirs.begin(), dirs.end());
  std::reverse(angles.begin(), angles.end());
  ASSERT_NO_FATAL_FAILURE(expect_fan_matches(*rw.world, o, dirs, angles, 5.0, false));
}

TEST(FanCast, SenseRangesMatchesSensorBySensorWithNoise) {
  Rng world_rng(77);
  const RandomWorld rw = random_world(world_rng, true);
  const World& w = *rw.world;
  // A lidar, an IR cone and a second lidar with another range: three runs.
  std::vector<RangeSensorSpec> sensors =
      make_lidar(180, 2.0 * kPi, 0.12, 3.5, {Vec2(-0.03, 0.0), 0.0});
  sensors.push_back({{Vec2(0.1, 0.0), 0.0}, 0.02, 0.3, 0.3, 5});
  for (const RangeSensorSpec& s :
       make_lidar(40, deg_to_rad(270.0), 0.1, 8.0, {Vec2(0.1, 0.0), 0.0}))
    sensors.push_back(s);
  std::vector<SensorBeam> beams(sensors.size());
  std::vector<double> fast(sensors.size()), slow(sensors.size());
  Rng pose_rng(3);
  for (int i = 0; i < 300; ++i) {
    const Box2 e = w.extent();
    const Pose2 robot{
        Vec2(pose_rng.uniform(e.min.x(), e.max.x()), pose_rng.uniform(e.min.y(), e.max.y())),
        pose_rng.uniform(-kPi, kPi)};
    compute_sensor_beams(robot, sensors, beams);
    const FreeDisc free{robot.position,
                        i % 2 == 0 ? std::max(0.0, w.clearance(robot.position)) : 0.0};
    Rng a(100 + i), b(100 + i);
    sense_ranges(w, beams, sensors, 0.01, a, fast, shared_scratch(), free);
    for (std::size_t k = 0; k < sensors.size(); ++k) {
      const RangeSensorSpec& s = sensors[k];
      double r = s.max_range;
      if (s.cone_rays <= 1) {
        r = w.cast_ray(beams[k].origin, beams[k].dir, s.max_range);
      } else {
        for (int j = 0; j < s.cone_rays; ++j) {
          const double ang =
              beams[k].theta + s.cone_angle * (static_cast<double>(j) / (s.cone_rays - 1) - 0.5);
          r = std::min(
              r, w.cast_ray(beams[k].origin, Vec2(std::cos(ang), std::sin(ang)), s.max_range));
        }
      }
      if (r < s.max_range) r += 0.01 * b.normal();
      slow[k] = std::clamp(r, s.min_range, s.max_range);
    }
    for (std::size_t k = 0; k < sensors.size(); ++k)
      ASSERT_EQ(bits(fast[k]), bits(slow[k])) << "pose " << i << " sensor " << k;
    EXPECT_EQ(a.normal(), b.normal());  // the same number of draws
  }
}

}  // namespace
}  // namespace floornav
