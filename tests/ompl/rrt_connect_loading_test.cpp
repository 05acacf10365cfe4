// OMPL is loaded on the first rrt_connect search, not before: a program that links floornav::ompl
// (so has the planner) but does not search with it never maps libompl, nor Boost and ODE with it.
// Its own executable, so that no other test has searched before it.
#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "floornav/nav/sampling_planner.hpp"
#include "floornav/ompl/rrt_connect.hpp"

namespace floornav {
namespace {

// Whether a file whose name contains `name` is mapped into this process.
bool mapped(const std::string& name) {
  std::ifstream maps("/proc/self/maps");
  for (std::string line; std::getline(maps, line);)
    if (line.find(name) != std::string::npos) return true;
  return false;
}

FreeRaster open_floor() {
  FreeRaster r;
  r.width = 20;
  r.height = 10;
  r.free.assign(static_cast<std::size_t>(r.width * r.height), 1);
  r.free[static_cast<std::size_t>(5 * r.width + 10)] = 0;  // one blocked cell
  return r;
}

TEST(RrtConnectLoading, OmplIsMappedOnTheFirstSearchOnly) {
  ASSERT_TRUE(std::ifstream("/proc/self/maps").good()) << "this test reads /proc/self/maps";
  EXPECT_EQ(rrt_connect_search(), &rrt_connect_path) << "linking floornav::ompl installs it";
  EXPECT_FALSE(mapped("libompl")) << "OMPL loaded before any search";

  // Plans that need no search: a blocked end, no budget, the goal at the start.
  const FreeRaster r = open_floor();
  std::vector<Vec2> path;
  EXPECT_FALSE(rrt_connect_path(r, {1, 1}, {10, 5}, 1, 1000, path));
  EXPECT_FALSE(rrt_connect_path(r, {1, 1}, {18, 8}, 1, 0, path));
  EXPECT_TRUE(rrt_connect_path(r, {1, 1}, {1, 1}, 1, 1000, path));
  EXPECT_EQ(path.size(), 2u);
  EXPECT_FALSE(mapped("libompl")) << "OMPL loaded for a plan that needs no search";
  EXPECT_FALSE(mapped("libfloornav_rrt_connect"));

  // The first search loads the module and OMPL with it, and finds the path.
  ASSERT_TRUE(rrt_connect_path(r, {1, 1}, {18, 8}, 1, 1000, path));
  EXPECT_EQ(path.front(), Vec2(1.5, 1.5));
  EXPECT_EQ(path.back(), Vec2(18.5, 8.5));
  EXPECT_TRUE(mapped("libfloornav_rrt_connect.so"));
  EXPECT_TRUE(mapped("libompl"));
}

}  // namespace
}  // namespace floornav
