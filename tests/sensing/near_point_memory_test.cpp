#include "floornav/sensing/near_point_memory.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace floornav {
namespace {

bool holds(std::span<const Vec2> points, const Vec2& q) {
  for (const Vec2& p : points)
    if (p == q) return true;
  return false;
}

TEST(NearPointMemory, KeepsNearReturnsAfterTheyLeaveTheScan) {
  NearPointMemory memory(1.0, 1.0, 0.03);
  // Seen once, 0.5 m ahead; then not seen again (the lidar's blind sector), for any time.
  memory.update(std::vector<Vec2>{{0.5, 0.0}}, Vec2::Zero(), {});
  for (int step = 0; step < 1000; ++step) memory.update({}, Vec2(0.2, 0.0), {});
  ASSERT_EQ(memory.points().size(), 1U);
  EXPECT_EQ(memory.points()[0], Vec2(0.5, 0.0));
}

TEST(NearPointMemory, ForgetsWhatTheRobotLeftBeyondKeep) {
  NearPointMemory memory(1.0, 1.0, 0.03);
  memory.update(std::vector<Vec2>{{0.5, 0.0}, {-0.9, 0.0}}, Vec2::Zero(), {});
  // From (0.2, 0): (0.5, 0) is 0.3 m away, (-0.9, 0) 1.1 m: forgotten.
  const auto kept = memory.update({}, Vec2(0.2, 0.0), {});
  ASSERT_EQ(kept.size(), 1U);
  EXPECT_EQ(kept[0], Vec2(0.5, 0.0));
  // Returning does not bring it back: it was forgotten.
  EXPECT_EQ(memory.update({}, Vec2::Zero(), {}).size(), 1U);
}

TEST(NearPointMemory, KeepsOneReturnPerSquareAndOnlyNearOnes) {
  NearPointMemory memory(1.0, 1.0, 0.03);
  // (0.301, 0.001) and (0.329, 0.029) share the square [0.30, 0.33) x [0, 0.03); (0.331, 0)
  // is the next one; (1.2, 0) is beyond keep.
  const std::vector<Vec2> scan{{0.301, 0.001}, {0.329, 0.029}, {0.331, 0.0}, {1.2, 0.0}};
  const auto kept = memory.update(scan, Vec2::Zero(), {});
  ASSERT_EQ(kept.size(), 2U);
  EXPECT_TRUE(holds(kept, {0.301, 0.001}));  // the first seen
  EXPECT_TRUE(holds(kept, {0.331, 0.0}));
  // Seen again: nothing new.
  EXPECT_EQ(memory.update(scan, Vec2::Zero(), {}).size(), 2U);
}

TEST(NearPointMemory, SquaresAcrossTheAxesAreDistinct) {
  NearPointMemory memory(1.0, 1.0, 0.03);
  // floor, not truncation: -0.01 and 0.01 lie in different squares.
  const auto kept =
      memory.update(std::vector<Vec2>{{0.01, 0.01}, {-0.01, 0.01}, {0.01, -0.01}, {-0.01, -0.01}},
                    Vec2::Zero(), {});
  EXPECT_EQ(kept.size(), 4U);
}

TEST(NearPointMemory, ReturnsOnMovingBodiesAreNotKept) {
  NearPointMemory memory(1.0, 1.0, 0.03);
  const std::vector<Circle> moving{{Vec2(0.5, 0.0), 0.1}};
  const auto kept = memory.update(std::vector<Vec2>{{0.41, 0.0}, {0.5, 0.3}}, Vec2::Zero(), moving);
  ASSERT_EQ(kept.size(), 1U);
  EXPECT_EQ(kept[0], Vec2(0.5, 0.3));
}

TEST(NearPointMemory, NotANumberIsNotKept) {
  NearPointMemory memory(1.0, 1.0, 0.03);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(memory.update(std::vector<Vec2>{{nan, 0.0}, {inf, 0.0}}, Vec2::Zero(), {}).empty());
}

TEST(NearPointMemory, AFullMemoryKeepsWhatItHasAndTakesMoreWhenRoomFrees) {
  NearPointMemory memory(10.0, 10.0, 0.03);
  std::vector<Vec2> many;
  for (std::size_t k = 0; k < NearPointMemory::kCapacity + 10; ++k)
    many.emplace_back(0.05 * static_cast<double>(k % 100), 0.05 * static_cast<double>(k / 100));
  EXPECT_EQ(memory.update(many, Vec2::Zero(), {}).size(), NearPointMemory::kCapacity);
  EXPECT_FALSE(holds(memory.points(), many.back()));
  // Moving 5 m away frees the squares beyond keep; the rest of the scan then fits.
  memory.update({}, Vec2(-5.5, 0.0), {});
  const std::size_t before = memory.points().size();
  ASSERT_LT(before, NearPointMemory::kCapacity);
  memory.update(std::vector<Vec2>{{-5.0, 0.0}}, Vec2(-5.5, 0.0), {});
  EXPECT_EQ(memory.points().size(), before + 1);
}

TEST(NearPointMemory, ClearForgetsEverything) {
  NearPointMemory memory(1.0, 1.0, 0.03);
  memory.update(std::vector<Vec2>{{0.5, 0.0}}, Vec2::Zero(), {});
  memory.clear();
  EXPECT_TRUE(memory.points().empty());
  // The square is free again.
  EXPECT_EQ(memory.update(std::vector<Vec2>{{0.5, 0.0}}, Vec2::Zero(), {}).size(), 1U);
}

TEST(NearPointMemory, ManyStepsOfForgettingKeepTheSquaresConsistent) {
  // Many refills (stamps) with points coming and going: every kept point's square is unique.
  NearPointMemory memory(0.5, 0.5, 0.03);
  const double kInv = 1.0 / 0.03;  // the memory's own squares
  for (int step = 0; step < 2000; ++step) {
    const Vec2 centre(0.001 * step, 0.0);
    std::vector<Vec2> scan;
    for (int k = 0; k < 40; ++k)
      scan.emplace_back(centre.x() + 0.4 * std::cos(0.15 * k), 0.4 * std::sin(0.15 * k));
    const auto kept = memory.update(scan, centre, {});
    for (const Vec2& p : kept) ASSERT_LE((p - centre).norm(), 0.5 + 1e-12);
    for (std::size_t a = 0; a < kept.size(); ++a)
      for (std::size_t b = a + 1; b < kept.size(); ++b)
        ASSERT_FALSE(std::floor(kept[a].x() * kInv) == std::floor(kept[b].x() * kInv) &&
                     std::floor(kept[a].y() * kInv) == std::floor(kept[b].y() * kInv))
            << "step " << step;
  }
}

}  // namespace
}  // namespace floornav

namespace floornav {
namespace {
TEST(NearPointMemory, AddsOnlyWithinAddButKeepsToKeep) {
  NearPointMemory memory(0.5, 1.0, 0.03);
  // (0.7, 0) lies beyond add: not added. (0.4, 0) is added, and kept from (-0.5, 0), 0.9 m off.
  EXPECT_EQ(memory.update(std::vector<Vec2>{{0.7, 0.0}, {0.4, 0.0}}, Vec2::Zero(), {}).size(), 1U);
  const auto kept = memory.update({}, Vec2(-0.5, 0.0), {});
  ASSERT_EQ(kept.size(), 1U);
  EXPECT_EQ(kept[0], Vec2(0.4, 0.0));
  EXPECT_TRUE(memory.update({}, Vec2(-0.7, 0.0), {}).empty());
}
}  // namespace
}  // namespace floornav
