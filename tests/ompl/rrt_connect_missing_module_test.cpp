// A program whose rrt_connect module is missing or of another build: the first search throws one
// error that names every place tried and why each was refused, and a later call tries again.
// This executable has no run path to the build directory, and beside it lies a module built
// with another ABI tag (a module of another build, as a stale install would be).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "floornav/ompl/rrt_connect.hpp"

namespace floornav {
namespace {

FreeRaster open_floor() {
  FreeRaster r;
  r.width = 20;
  r.height = 10;
  r.free.assign(static_cast<std::size_t>(r.width * r.height), 1);
  return r;
}

std::string search_error(const FreeRaster& r) {
  std::vector<Vec2> path;
  try {
    rrt_connect_path(r, {1, 1}, {18, 8}, 1, 1000, path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RrtConnectMissingModule, TheSearchNamesEveryPlaceTriedAndWhy) {
  const FreeRaster r = open_floor();
  const std::string what = search_error(r);
  EXPECT_NE(what.find("cannot load OMPL's planner module libfloornav_rrt_connect.so"),
            std::string::npos)
      << what;
  // Beside the program: a module, but of another build.
  EXPECT_NE(what.find("/libfloornav_rrt_connect.so: built from floornav 0.0.0 another-build"),
            std::string::npos)
      << what;
  // Then by name: nowhere on the (empty) run path.
  EXPECT_NE(what.find("\n  libfloornav_rrt_connect.so: "), std::string::npos) << what;
  // Not cached: the next search tries again, with the same answer.
  EXPECT_EQ(search_error(r), what);
  // Plans that need no search still work.
  std::vector<Vec2> path;
  EXPECT_TRUE(rrt_connect_path(r, {1, 1}, {1, 1}, 1, 1000, path));
}

}  // namespace
}  // namespace floornav
