#include "floornav/io/sdf_world.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <utility>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/io/barn.hpp"
#include "support/loader_test_support.hpp"

namespace floornav {
namespace {

namespace fs = std::filesystem;

class SdfWorldTest : public test::TempDirTest {};

using test::expect_input_error;

void expect_point(const Vec2& p, double x, double y) {
  EXPECT_NEAR(p.x(), x, 1e-12);
  EXPECT_NEAR(p.y(), y, 1e-12);
}

const std::string kWorld = R"(<?xml version="1.0" ?>
<sdf version='1.6'>
  <world name='w'>
    <include><uri>model://sun</uri></include>
    <model name='ground_plane'>
      <static>1</static>
      <link name='link'><collision name='c'><geometry><plane><normal>0 0 1</normal>
        <size>100 100</size></plane></geometry></collision></link>
    </model>
    <model name='shelf'>
      <static>true</static>
      <pose frame=''>1 2 0 0 0 1.5707963267948966</pose>
      <link name='l'>
        <pose>1 0 0 0 0 0</pose>
        <collision name='c'>
          <pose>0 1 0.5 0 0 0</pose>
          <geometry><box><size>2 1 1</size></box></geometry>
        </collision>
        <visual name='v'><geometry><box><size>9 9 9</size></box></geometry></visual>
      </link>
    </model>
    <model name='post'>
      <static>1</static>
      <pose>5 5 0 0 0 0</pose>
      <link name='l'><collision name='c'><geometry><cylinder><radius>0.2</radius>
        <length>1</length></cylinder></geometry></collision></link>
    </model>
    <model name='robot'>
      <pose>0 0 0 0 0 0</pose>
      <link name='base'><collision name='c'><geometry><box><size>1 1 1</size></box></geometry>
      </collision></link>
    </model>
    <model name='statue'>
      <static>1</static>
      <link name='l'><collision name='c'><geometry><mesh><uri>x.dae</uri></mesh></geometry>
      </collision></link>
    </model>
    <model name='outer'>
      <static>1</static>
      <pose>10 0 0 0 0 0</pose>
      <model name='inner'>
        <pose>0 1 0 0 0 0</pose>
        <link name='l'><collision name='c'><geometry><sphere><radius>0.5</radius></sphere>
        </geometry></collision></link>
      </model>
    </model>
    <state world_name='w'>
      <model name='post'>
        <pose frame=''>7 -1 0 0 0 0</pose>
        <link name='l'><pose frame=''>7 -1 0 0 0 0</pose></link>
      </model>
      <model name='ground_plane'><pose frame=''>0 0 0 0 -0 0</pose></model>
    </state>
  </world>
</sdf>
)";

TEST_F(SdfWorldTest, ComposesPosesAndPrefersTheState) {
  const SdfWorld w = load_sdf_world(write("w.world", kWorld));
  // Shelf: model (1, 2, 90 deg) * link (1, 0) = (1, 3); * collision (0, 1) = (0, 3), yaw 90 deg.
  // The 2 x 1 box turned 90 deg spans x in [-0.5, 0.5], y in [2, 4].
  ASSERT_EQ(w.polygons.size(), 1u);
  ASSERT_EQ(w.polygons[0].size(), 4u);
  expect_point(w.polygons[0][0], 0.5, 2.0);
  expect_point(w.polygons[0][1], 0.5, 4.0);
  expect_point(w.polygons[0][2], -0.5, 4.0);
  expect_point(w.polygons[0][3], -0.5, 2.0);
  // The post at its <state> pose (7, -1), once; the nested sphere at (10, 0) + (0, 1).
  ASSERT_EQ(w.circles.size(), 2u);
  expect_point(w.circles[0].center, 7.0, -1.0);
  EXPECT_EQ(w.circles[0].radius, 0.2);
  expect_point(w.circles[1].center, 10.0, 1.0);
  EXPECT_EQ(w.circles[1].radius, 0.5);
  // The non-static robot and the mesh are reported, with their lines; the sun and the ground
  // plane hold nothing to hit and are not.
  ASSERT_EQ(w.skipped.size(), 2u);
  EXPECT_NE(w.skipped[0].find(": model 'robot' is not static"), std::string::npos) << w.skipped[0];
  EXPECT_EQ(w.skipped[0].rfind("line ", 0), 0u);
  EXPECT_NE(w.skipped[1].find("model 'statue::l': a <mesh> collision cannot be read"),
            std::string::npos)
      << w.skipped[1];
}

TEST_F(SdfWorldTest, BareModelFileAndDegrees) {
  const SdfWorld w = load_sdf_world(write("m.sdf", R"(<sdf version='1.9'>
  <model name='m'><static>true</static><pose degrees='true'>0 0 0 0 0 90</pose>
    <link name='l'><collision name='c'><pose>2 0 0 0 0 0</pose>
      <geometry><cylinder><radius>1</radius><length>1</length></cylinder></geometry>
    </collision></link></model></sdf>)"));
  ASSERT_EQ(w.circles.size(), 1u);
  expect_point(w.circles[0].center, 0.0, 2.0);
}

/// The bounding box of a polygon.
std::pair<Vec2, Vec2> extent_of(const std::vector<Vec2>& poly) {
  Vec2 lo = poly.front(), hi = poly.front();
  for (const Vec2& p : poly) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  return {lo, hi};
}

// A tilted shape covers its ground shadow, not its upright footprint: a box on its side, a
// cylinder lying down (it once kept the footprint it has standing, dropping most of it). A chain
// of tilts that cancels is upright again, and a sphere is a disc however it is turned.
TEST_F(SdfWorldTest, TiltedShapesCoverTheirGroundShadow) {
  auto model = [](const std::string& name, const std::string& pose, const std::string& link_pose,
                  const std::string& shape) {
    return "<model name='" + name + "'><static>1</static><pose>" + pose +
           "</pose><link name='l'><pose>" + link_pose + "</pose><collision name='c'><geometry>" +
           shape + "</geometry></collision></link></model>\n";
  };
  const SdfWorld w = load_sdf_world(write(
      "tilt.world",
      "<sdf version='1.6'><world name='w'>\n" +
          // A 2 x 1 x 0.5 box pitched 90 degrees: 0.5 along x, 1 along y (upright: 2 along x).
          model("box", "5 0 0 0 1.5707963267948966 0", "0 0 0 0 0 0",
                "<box><size>2 1 0.5</size></box>") +
          // A cylinder of radius 0.2 and length 2 lying along y.
          model("log", "0 5 0 1.5707963267948966 0 0", "0 0 0 0 0 0",
                "<cylinder><radius>0.2</radius><length>2</length></cylinder>") +
          // Rolled there and back again: upright, a disc.
          model("post", "0 -5 0 0.7 0 0", "0 0 0 -0.7 0 0",
                "<cylinder><radius>0.3</radius><length>1</length></cylinder>") +
          model("ball", "-5 0 1 0.4 0.9 0", "0 0 0 0 0 0",
                "<sphere><radius>0.5</radius></sphere>") +
          "</world></sdf>"));
  ASSERT_TRUE(w.skipped.empty());
  ASSERT_EQ(w.polygons.size(), 2u);
  const auto [box_lo, box_hi] = extent_of(w.polygons[0]);
  EXPECT_NEAR(box_lo.x(), 4.75, 1e-9);
  EXPECT_NEAR(box_hi.x(), 5.25, 1e-9);
  EXPECT_NEAR(box_lo.y(), -0.5, 1e-9);
  EXPECT_NEAR(box_hi.y(), 0.5, 1e-9);
  EXPECT_TRUE(is_simple(w.polygons[0]));
  const auto [log_lo, log_hi] = extent_of(w.polygons[1]);
  EXPECT_NEAR(log_lo.y(), 4.0, 1e-9);  // the length, lying along y
  EXPECT_NEAR(log_hi.y(), 6.0, 1e-9);
  EXPECT_LE(log_lo.x(), -0.2);  // never narrower than the cylinder ...
  EXPECT_GE(log_hi.x(), 0.2);
  EXPECT_LT(log_hi.x(), 0.21);                  // ... and barely wider
  EXPECT_GT(signed_area(w.polygons[1]), 0.79);  // 2 x 0.4 m, counter-clockwise
  ASSERT_EQ(w.circles.size(), 2u);
  expect_point(w.circles[0].center, 0.0, -5.0);
  EXPECT_EQ(w.circles[0].radius, 0.3);
  expect_point(w.circles[1].center, -5.0, 0.0);
  EXPECT_EQ(w.circles[1].radius, 0.5);
}

TEST_F(SdfWorldTest, BadWorlds) {
  auto world = [](const std::string& models) {
    return "<sdf version='1.6'><world name='w'>\n" + models + "</world></sdf>";
  };
  auto cylinder = [](const std::string& name, const std::string& pose) {
    return "<model name='" + name + "'><static>1</static><pose>" + pose +
           "</pose><link name='l'><collision name='c'><geometry><cylinder><radius>1</radius>"
           "</cylinder></geometry></collision></link></model>\n";
  };
  struct Case {
    std::string text;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {world(cylinder("a", "1 2 0 0 0")), "line 2: <pose>: expected 6 numbers, got 5"},
      {world(cylinder("a", "1 2 x 0 0 0")), "<pose>: 'x' is not a finite number"},
      {world(cylinder("a", "1 nan 0 0 0 0")), "'nan' is not a finite number"},
      {world(cylinder("a", "1 2 0 0 0 0") + cylinder("a", "3 4 0 0 0 0")),
       "line 3: duplicate model name 'a'"},
      {world("<model name='a'><static>1</static><pose relative_to='b'>0 0 0 0 0 0</pose></model>"),
       "poses relative to other frames are not supported"},
      {world("<model name='a'><static>yes</static></model>"),
       "<static> must be 0, 1, true or false"},
      {world("<model name='a'><static>1</static><link name='l'><collision name='c'><geometry>"
             "<box><size>1 -2 1</size></box></geometry></collision></link></model>"),
       "<size> must be positive"},
      {world("<model name='a'><static>1</static><link name='l'><collision name='c'><geometry>"
             "<box><size>1 2</size></box></geometry></collision></link></model>"),
       "<size>: expected 3 numbers, got 2"},
      {world("<model name='a'><static>1</static><link name='l'><collision name='c'><geometry>"
             "<cylinder><length>1</length></cylinder></geometry></collision></link></model>"),
       "<cylinder> lacks <radius>"},
      {world("<model name='a'><static>1</static><link name='l'><collision name='c'>"
             "</collision></link></model>"),
       "<collision> without a <geometry> shape"},
      {"<world name='w'></world>", "expected an <sdf> root"},
      {"<sdf version='1.6'><light name='sun'/></sdf>", "no <world> or <model>"},
      {"<sdf version='1.6'><world name='w'>\n<model name='a'>\n</world></sdf>", "malformed XML"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const fs::path p = write("bad.world", cases[i].text);
    expect_input_error([&] { load_sdf_world(p); }, cases[i].needle);
  }
  expect_input_error([&] { load_sdf_world(dir_ / "none.world"); }, "does not exist");
}

fs::path barn() {
  return fs::path(FLOORNAV_MAPS_DIR) / "barn/world_files";
}

TEST(SdfWorldRealFiles, BarnWorlds) {
  // Unique unit_cylinder_K models, counted with
  //   grep -o "<model name='unit_cylinder_[0-9]*'" world_N.world | sort -u | wc -l
  // (each appears twice: as a model and again under <state>).
  const std::pair<const char*, std::size_t> worlds[] = {
      {"world_0.world", 209}, {"world_150.world", 292}, {"world_299.world", 277}};
  for (const auto& [name, count] : worlds) {
    SCOPED_TRACE(name);
    const SdfWorld w = load_sdf_world(barn() / name);
    EXPECT_EQ(w.circles.size(), count);
    EXPECT_TRUE(w.polygons.empty());
    EXPECT_TRUE(w.skipped.empty());
    std::set<std::pair<long, long>> cells;
    for (const Circle& c : w.circles) {
      EXPECT_EQ(c.radius, 0.075);
      // On the 0.15 m lattice x = -0.075 - 0.15 i, y = 0.075 + 0.15 j (SOURCES.md section 7).
      const double i = (-0.075 - c.center.x()) / 0.15;
      const double j = (c.center.y() - 0.075) / 0.15;
      EXPECT_NEAR(i, std::round(i), 1e-9);
      EXPECT_NEAR(j, std::round(j), 1e-9);
      EXPECT_GE(std::round(i), 0.0);
      EXPECT_LE(std::round(i), 29.0);
      cells.insert({std::lround(i), std::lround(j)});
    }
    EXPECT_EQ(cells.size(), count);  // no duplicates
  }
  // world_150.world, model unit_cylinder_100:
  //   <pose frame=''>-4.425000 5.775000 0.000000 0.000000 0.000000 0.000000</pose>
  //   <radius>0.075000</radius>
  const SdfWorld w = load_sdf_world(barn() / "world_150.world");
  ASSERT_GT(w.circles.size(), 100u);
  EXPECT_EQ(w.circles[100].center, Vec2(-4.425, 5.775));
  EXPECT_EQ(w.circles[100].radius, 0.075);
}

// BARN's reference paths load strictly: every real path_N.npy is an (n, 2) int64 array of cells
// inside the 30 x 30 grid.
TEST(SdfWorldRealFiles, BarnPaths) {
  const fs::path dir = fs::path(FLOORNAV_MAPS_DIR) / "barn/path_files";
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    const auto cells = load_barn_path(e.path());
    EXPECT_FALSE(cells.empty());
    ++files;
  }
  EXPECT_EQ(files, 300);
  // path_0.npy starts at cell (26, 0) (its first 16 bytes of data, read by hand).
  EXPECT_EQ(load_barn_path(dir / "path_0.npy").front()[0], 26);
  EXPECT_EQ(load_barn_path(dir / "path_0.npy").front()[1], 0);
}

}  // namespace
}  // namespace floornav
