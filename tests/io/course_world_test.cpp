#include "floornav/io/course_world.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "floornav/core/input_error.hpp"
#include "support/loader_test_support.hpp"

namespace floornav {
namespace {

namespace fs = std::filesystem;

class CourseWorldTest : public test::TempDirTest {};

using test::expect_input_error;

// Shaped like pySimiam's worlds/week7.xml.
const std::string kWeek7Like = R"(<?xml version="1.0" ?>
<simulation>
  <robot type="QuickBot">
    <supervisor type="week7.QBFullSupervisor" />
    <pose x="0" y="0" theta="0" />
  </robot>
  <obstacle>
    <pose x="-0.4" y="0.2" theta="0" />
    <geometry>
      <point x="0" y="0" />
      <point x="0.8" y="0" />
      <point x="0.8" y="0.1" />
      <point x="0" y="0.1" />
    </geometry>
  </obstacle>
  <obstacle color="0xff0000">
    <pose x="1" y="2" theta="1.5707963267948966" />
    <geometry><point x="0" y="0"/><point x="1" y="0"/><point x="0" y="0.5"/></geometry>
  </obstacle>
  <marker>
    <pose x="1" y="1" theta="0" />
    <geometry><point x="0" y="0"/></geometry>
  </marker>
  <robot type="Khepera3">
    <pose x="1.5" y="-0.25" theta="-0.5" />
  </robot>
</simulation>
)";

TEST_F(CourseWorldTest, Week7Like) {
  const CourseWorld w = load_course_world(write("week7.xml", kWeek7Like));
  ASSERT_EQ(w.robots.size(), 2u);
  EXPECT_EQ(w.robots[0].type, "QuickBot");
  EXPECT_EQ(w.robots[0].supervisor, "week7.QBFullSupervisor");
  EXPECT_EQ(w.robots[0].pose.position, Vec2(0.0, 0.0));
  EXPECT_EQ(w.robots[0].pose.theta, 0.0);
  EXPECT_EQ(w.robots[1].type, "Khepera3");
  EXPECT_EQ(w.robots[1].supervisor, "");
  EXPECT_EQ(w.robots[1].pose.position, Vec2(1.5, -0.25));
  EXPECT_EQ(w.robots[1].pose.theta, -0.5);

  ASSERT_EQ(w.obstacles.size(), 2u);  // the marker is not an obstacle
  const auto& wall = w.obstacles[0];
  ASSERT_EQ(wall.size(), 4u);
  EXPECT_NEAR(wall[0].x(), -0.4, 1e-15);
  EXPECT_NEAR(wall[0].y(), 0.2, 1e-15);
  EXPECT_NEAR(wall[2].x(), 0.4, 1e-15);
  EXPECT_NEAR(wall[2].y(), 0.3, 1e-15);
  // Rotated 90 deg about (1, 2): (1, 0) -> (1, 3), (0, 0.5) -> (0.5, 2).
  const auto& tri = w.obstacles[1];
  ASSERT_EQ(tri.size(), 3u);
  EXPECT_NEAR(tri[0].x(), 1.0, 1e-12);
  EXPECT_NEAR(tri[0].y(), 2.0, 1e-12);
  EXPECT_NEAR(tri[1].x(), 1.0, 1e-12);
  EXPECT_NEAR(tri[1].y(), 3.0, 1e-12);
  EXPECT_NEAR(tri[2].x(), 0.5, 1e-12);
  EXPECT_NEAR(tri[2].y(), 2.0, 1e-12);
}

TEST_F(CourseWorldTest, BadWorlds) {
  const std::string robot = R"(<robot type="QuickBot"><pose x="0" y="0" theta="0"/></robot>)";
  struct Case {
    std::string text;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {"<simulation>\n<obstacle>\n<pose x='0' y='0' theta='0'/>\n<geometry><point x='0' y='0'/>"
       "<point x='1' y='0'/></geometry></obstacle></simulation>",
       "line 2: an obstacle needs at least 3 <point>s, got 2"},
      {"<simulation>\n<obstacle><pose x='0' y='0' theta='0'/><geometry>\n<point x='abc' y='0'/>"
       "<point x='1' y='0'/><point x='1' y='1'/></geometry></obstacle></simulation>",
       "line 3: <point x=\"abc\">: expected a finite number"},
      {"<simulation><obstacle><pose x='0' y='nan' theta='0'/><geometry><point x='0' y='0'/>"
       "<point x='1' y='0'/><point x='1' y='1'/></geometry></obstacle></simulation>",
       "<pose y=\"nan\">: expected a finite number"},
      {"<simulation><obstacle><pose x='0' y='1.5m' theta='0'/><geometry/></obstacle></simulation>",
       "expected a finite number"},
      {"<simulation><robot type='QuickBot'><pose x='0' y='0'/></robot></simulation>",
       "<pose> lacks the attribute 'theta'"},
      {"<simulation><robot type='QuickBot'></robot></simulation>", "<robot> lacks a <pose"},
      {"<simulation><robot><pose x='0' y='0' theta='0'/></robot></simulation>",
       "<robot> lacks the attribute 'type'"},
      {"<simulation><obstacle><pose x='0' y='0' theta='0'/></obstacle></simulation>",
       "<obstacle> lacks a <geometry>"},
      {"<world>" + robot + "</world>", "expected a <simulation> root"},
      {"<simulation>\n" + robot + "\n<obstacle>\n</simulation>", "line 3: malformed XML"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const fs::path p = write("bad.xml", cases[i].text);
    expect_input_error([&] { load_course_world(p); }, cases[i].needle);
  }
  expect_input_error([&] { load_course_world(dir_ / "none.xml"); }, "does not exist");
}

}  // namespace
}  // namespace floornav
