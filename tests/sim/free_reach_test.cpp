// sense_ranges with a free disc that holds a sensor's whole reach: the world's cells are not
// walked then, and the ranges must still be the world's, bit for bit, with the same noise draws;
// what the disc does not cover (the occupancy grid, other robots' bodies) is still seen.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sensing/sensor_fans.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"
#include "support/bits.hpp"

namespace floornav {
namespace {

using test::bits;

// A 12 m hall with 4 m racks in rows 3 m apart, and a few pillars.
World rack_hall() {
  WorldDesc d;
  d.bounds = Box2{Vec2(0.0, 0.0), Vec2(12.0, 12.0)};
  for (double y = 2.0; y + 1.0 <= 10.0; y += 3.0)
    for (double x = 2.0; x + 4.0 <= 10.0; x += 5.0)
      d.polygons.push_back(
          {Vec2(x, y), Vec2(x + 4.0, y), Vec2(x + 4.0, y + 1.0), Vec2(x, y + 1.0)});
  d.circles.push_back({Vec2(1.0, 1.0), 0.2});
  d.circles.push_back({Vec2(6.5, 10.5), 0.3});
  return World(std::move(d));
}

// A QuickBot's 5 IR beams plus a 5-ray cone sensor.
std::vector<RangeSensorSpec> ir_sensors() {
  std::vector<RangeSensorSpec> sensors = find_robot_preset("quickbot")->robot.sensors;
  sensors.push_back({{Vec2(0.05, 0.0), 0.0}, 0.02, 0.4, 0.3, 5});
  return sensors;
}

TEST(FreeReach, RangesAndNoiseDrawsAreTheWorldsBitForBit) {
  const World w = rack_hall();
  const std::vector<RangeSensorSpec> sensors = ir_sensors();
  std::vector<SensorBeam> beams(sensors.size());
  std::vector<double> with_disc(sensors.size()), without(sensors.size());
  FanScratch scratch;
  Rng pose_rng(11);
  int whole_reach_free = 0, saw_world = 0;
  for (int i = 0; i < 4000; ++i) {
    const Pose2 robot{Vec2(pose_rng.uniform(0.0, 12.0), pose_rng.uniform(0.0, 12.0)),
                      pose_rng.uniform(-kPi, kPi)};
    const double clearance = w.clearance(robot.position);
    if (clearance <= 0.08) continue;  // the sensors' mounts must lie in the disc
    compute_sensor_beams(robot, sensors, beams);
    Rng a(500 + i), b(500 + i);
    sense_ranges(w, beams, sensors, 0.01, a, with_disc, scratch,
                 FreeDisc{robot.position, clearance});
    sense_ranges(w, beams, sensors, 0.01, b, without, scratch);
    for (std::size_t k = 0; k < sensors.size(); ++k)
      ASSERT_EQ(bits(with_disc[k]), bits(without[k])) << "pose " << i << " sensor " << k;
    EXPECT_EQ(a.normal(), b.normal());  // the same number of draws
    // Both cases occur: every beam's reach inside the disc, and walls within reach.
    whole_reach_free += clearance > 0.07 + 0.4 + 1e-3;
    for (std::size_t k = 0; k < sensors.size(); ++k)
      if (without[k] < sensors[k].max_range) {
        ++saw_world;
        break;
      }
  }
  EXPECT_GT(whole_reach_free, 500);
  EXPECT_GT(saw_world, 200);
}

TEST(FreeReach, TheOccupancyGridIsStillSeen) {
  // One occupied cell 0.2 m ahead; the disc holds no shape (the bounds are 5 m away) but says
  // nothing of the grid.
  std::vector<std::uint8_t> cells(100 * 100, 0);
  cells[50 * 100 + 52] = 1;  // x in [5.2, 5.3), y in [5.0, 5.1)
  auto grid = std::make_shared<const OccupancyGrid>(100, 100, 0.1, Pose2{}, cells);
  WorldDesc d;
  d.bounds = Box2{Vec2(0.0, 0.0), Vec2(10.0, 10.0)};
  d.grid = grid;
  const World w(std::move(d));
  const std::vector<RangeSensorSpec> sensors{{{Vec2::Zero(), 0.0}, 0.02, 0.3, 0.0, 1}};
  const Pose2 robot{Vec2(5.0, 5.05), 0.0};
  std::vector<SensorBeam> beams(1);
  compute_sensor_beams(robot, sensors, beams);
  std::vector<double> range(1);
  Rng rng(1);
  FanScratch scratch;
  sense_ranges(w, beams, sensors, 0.0, rng, range, scratch, FreeDisc{robot.position, 5.0});
  EXPECT_NEAR(range[0], 0.2, 1e-12);  // the cell's near face at x = 5.2
  EXPECT_EQ(bits(range[0]), bits(w.cast_ray(beams[0].origin, beams[0].dir, 0.3)));
}

TEST(FreeReach, OtherBodiesInTheDiscAreStillSeen) {
  const World w = rack_hall();
  // The QuickBot's front IR at (0.0664, 0) looking along +x; another robot's body (r 0.075)
  // centred 0.3 m ahead of the robot: hit at 0.3 - 0.075 - 0.0664 = 0.1586 m.
  const std::vector<RangeSensorSpec> sensors = find_robot_preset("quickbot")->robot.sensors;
  const Pose2 robot{Vec2(6.0, 4.0), 0.0};
  ASSERT_GT(w.clearance(robot.position), 0.9);  // the whole reach lies in the free disc
  std::vector<SensorBeam> beams(sensors.size());
  compute_sensor_beams(robot, sensors, beams);
  std::vector<double> ranges(sensors.size());
  const Circle other{robot.position + Vec2(0.3, 0.0), 0.075};
  Rng rng(1);
  FanScratch scratch;
  sense_ranges(w, beams, sensors, 0.0, rng, ranges, scratch,
               FreeDisc{robot.position, w.clearance(robot.position)}, std::span(&other, 1));
  EXPECT_NEAR(ranges[2], 0.1586, 1e-12);
  for (const std::size_t k : {0u, 1u, 3u, 4u}) EXPECT_EQ(ranges[k], sensors[k].max_range);
}

}  // namespace
}  // namespace floornav
