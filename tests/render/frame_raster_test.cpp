// FrameRaster: RGB frames of a floor with the bodies on it, north up, the world fitted with a
// margin; what is drawn lands where it stands, and nothing is drawn outside the buffer.
#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <vector>

#include "floornav/render/frame_raster.hpp"
#include "floornav/world/world.hpp"

using namespace floornav;

namespace {

Rgb at(const std::vector<std::uint8_t>& rgb, const FrameRaster& f, const Vec2& world_point) {
  const Vec2 px = f.to_pixel(world_point);
  const std::size_t k =
      3 * (static_cast<std::size_t>(px.y()) * static_cast<std::size_t>(f.width()) +
           static_cast<std::size_t>(px.x()));
  return {rgb[k], rgb[k + 1], rgb[k + 2]};
}

bool same(Rgb a, Rgb b) {
  return a.r == b.r && a.g == b.g && a.b == b.b;
}

World square_room() {
  WorldDesc d;
  d.bounds = Box2{Vec2(0.0, 0.0), Vec2(10.0, 10.0)};
  d.circles.push_back({{7.0, 7.0}, 1.0});
  return World(d);
}

}  // namespace

TEST(FrameRaster, DrawsTheWorldAndTheBodiesWhereTheyStand) {
  const World w = square_room();
  const FrameRaster f(w, 100, 160, std::nullopt);
  EXPECT_EQ(f.height(), 100);
  EXPECT_EQ(f.width(), 160);
  std::vector<std::uint8_t> rgb(f.bytes());
  const Rgb blue{31, 119, 180};
  const std::array<Vec2, 0> none{};
  FrameRobot robot;
  robot.pose = Pose2{{3.0, 2.0}, 0.0};
  robot.radius = 0.5;
  robot.goal = Vec2(8.0, 2.0);
  robot.returns = none;
  robot.colour = blue;
  const std::array<Circle, 1> people{Circle{{2.0, 8.0}, 0.4}};
  f.draw(rgb, {&robot, 1}, people);
  EXPECT_TRUE(same(at(rgb, f, {7.0, 7.0}), Rgb{201, 204, 209}));  // the obstacle
  EXPECT_TRUE(same(at(rgb, f, {5.0, 5.0}), Rgb{255, 255, 255}));  // the floor
  EXPECT_TRUE(same(at(rgb, f, {2.9, 1.9}), blue));                // the robot's body
  EXPECT_TRUE(same(at(rgb, f, {2.0, 8.0}), Rgb{123, 63, 160}));   // the person
  EXPECT_TRUE(same(at(rgb, f, {8.0, 2.0}), blue));                // the goal's cross
  // North up: a point above another is drawn in a row above it.
  EXPECT_LT(f.to_pixel({5.0, 9.0}).y(), f.to_pixel({5.0, 1.0}).y());
  // The next frame starts from the bare world: the robot moved, its old place is floor again.
  robot.pose.position = Vec2(5.0, 5.0);
  f.draw(rgb, {&robot, 1});
  EXPECT_TRUE(same(at(rgb, f, {2.9, 1.9}), Rgb{255, 255, 255}));
  EXPECT_TRUE(same(at(rgb, f, {4.9, 4.9}), blue));
}

TEST(FrameRaster, BodiesOffTheFrameAndWrongBuffersAreSafe) {
  const World w = square_room();
  const FrameRaster f(w, 32, 32, std::nullopt);
  std::vector<std::uint8_t> rgb(f.bytes());
  FrameRobot far;
  far.pose = Pose2{{-500.0, 900.0}, 1.0};
  far.radius = 50.0;
  far.goal = Vec2(1e6, -1e6);
  f.draw(rgb, {&far, 1});  // clipped, no write outside the buffer (ASan checks it)
  std::vector<std::uint8_t> small(10);
  EXPECT_THROW(f.draw(small, {}), std::invalid_argument);
  EXPECT_THROW(FrameRaster(w, 4, 4, std::nullopt), std::invalid_argument);
}
