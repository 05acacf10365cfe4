// trajectory.svg for fleets, footprints and maps with unknown cells (the basics of the picture
// are in tests/runner/outputs_test.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "floornav/render/palette.hpp"
#include "floornav/render/trajectory_svg.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// A straight run of `steps` samples from `from` along x, all in go_to_goal.
RunResult straight_run(const std::string& name, Vec2 from, int steps) {
  RunResult r;
  r.scenario = name;
  r.status = RunStatus::Reached;
  r.reached_goal = true;
  r.mode_names = {"go_to_goal", "follow_boundary_cw", "stop"};
  r.guard_names = {"at_goal"};
  r.mode_time = {0.01 * steps, 0.0, 0.0};
  for (int i = 0; i <= steps; ++i)
    r.trajectory.push_back({0.01 * i, from.x() + 0.01 * i, from.y(), 0.0, 1.0, 0.0, 0, 0, 0});
  r.final_x = r.trajectory.back().x;
  r.final_y = r.trajectory.back().y;
  r.steps = steps;
  return r;
}

Scenario fleet_of(int n) {
  Scenario s;
  s.name = "hall";
  WorldDesc desc;
  desc.bounds = Box2{Vec2(-1.0, -1.0), Vec2(4.0, 4.0)};
  s.world = std::make_shared<const World>(std::move(desc));
  s.robots_listed = true;
  for (int i = 0; i < n; ++i) {
    RobotTask t;
    t.name = "bot" + std::to_string(i);
    t.start = Pose2{Vec2(0.0, 0.5 * i), 0.0};
    t.goals = {Vec2(2.0, 0.5 * i), Vec2(3.0, 0.5 * i)};
    s.robots.push_back(t);
  }
  return s;
}

FleetResult fleet_result(const Scenario& s) {
  FleetResult f;
  f.scenario = s.name;
  for (const RobotTask& t : s.robots)
    f.robots.push_back(straight_run(t.name, t.start.position, 50));
  return f;
}

TEST(RobotColor, FirstColoursDistinctThenGoldenAngleHues) {
  std::vector<std::string> colors;
  for (std::size_t i = 0; i < 40; ++i) colors.push_back(robot_color(i));
  for (std::size_t i = 0; i < colors.size(); ++i) {
    EXPECT_EQ(colors[i].size(), 7u);
    EXPECT_EQ(colors[i][0], '#');
    if (i > 0) {
      EXPECT_NE(colors[i], colors[i - 1]) << i;
    }
  }
  EXPECT_EQ(robot_color(0), "#1b9e77");
  // Index 8 is the first generated hue: h = 0, so HSL(0, 65 %, 42 %) = rgb(177, 37, 37).
  EXPECT_EQ(robot_color(8), "#b12525");
}

TEST(FleetSvg, EachRobotInItsColourWithANamedLegend) {
  const Scenario s = fleet_of(3);
  const std::string svg = render_fleet_svg(s, fleet_result(s));
  for (std::size_t i = 0; i < 3; ++i) {
    // The path in the robot's colour, and a legend line of that colour beside its name.
    EXPECT_EQ(count_of(svg, "<polyline stroke=\"" + robot_color(i) + "\""), 1u) << i;
    EXPECT_NE(svg.find(">bot" + std::to_string(i) + "</text>"), std::string::npos);
  }
  // Paths are not coloured by mode in a fleet: no go_to_goal blue polyline, no mode legend.
  EXPECT_EQ(svg.find("<polyline stroke=\"#1f77b4\""), std::string::npos);
  EXPECT_EQ(svg.find(">go_to_goal</text>"), std::string::npos);
}

TEST(FleetSvg, GoalsNumberedPerRobotInTheRobotsColour) {
  const Scenario s = fleet_of(2);
  const std::string svg = render_fleet_svg(s, fleet_result(s));
  // Two goals per robot, numbered 1 and 2 for each robot, in its colour.
  EXPECT_EQ(count_of(svg, "class=\"goal-number\""), 4u);
  for (std::size_t i = 0; i < 2; ++i) {
    const std::string label = "fill=\"" + robot_color(i) + "\" stroke=\"#ffffff\"";
    EXPECT_EQ(count_of(svg, label), 2u) << i;
  }
  EXPECT_EQ(count_of(svg, "paint-order=\"stroke\">1</text>"), 2u);
  EXPECT_EQ(count_of(svg, "paint-order=\"stroke\">2</text>"), 2u);
}

TEST(FleetSvg, ALegendOfAHundredRobotsStopsAfterTwentyFourNames) {
  const Scenario s = fleet_of(100);
  const std::string svg = render_fleet_svg(s, fleet_result(s));
  EXPECT_NE(svg.find(">bot23</text>"), std::string::npos);
  EXPECT_NE(svg.find(">+ 76 more</text>"), std::string::npos);
  EXPECT_EQ(svg.find(">bot24</text>"), std::string::npos);
}

TEST(TrajectorySvg, AFootprintIsDrawnAsItsPolygon) {
  Scenario s = fleet_of(1);
  s.robots_listed = false;
  RobotTask& t = s.robot();
  t.robot.body_radius = 0.3;
  // A 0.5 x 0.4 m rectangle, pointing along x.
  t.robot.footprint = {Vec2(0.25, 0.2), Vec2(-0.25, 0.2), Vec2(-0.25, -0.2), Vec2(0.25, -0.2)};
  const RunResult r = straight_run("jackal", t.start.position, 100);
  const std::string svg = render_trajectory_svg(s, r);
  // Start and end bodies are the 4-corner polygon, not discs.
  std::vector<std::vector<double>> bodies;  // x0 y0 x1 y1 ... of each 4-corner polygon
  for (std::size_t at = svg.find("<polygon points=\""); at != std::string::npos;
       at = svg.find("<polygon points=\"", at + 1)) {
    const std::size_t begin = at + 17, end = svg.find('"', begin);
    std::string pts = svg.substr(begin, end - begin);
    if (count_of(pts, ",") != 4) continue;
    for (char& c : pts)
      if (c == ',') c = ' ';
    std::istringstream in(pts);
    std::vector<double> v(8);
    for (double& x : v) in >> x;
    bodies.push_back(v);
  }
  ASSERT_EQ(bodies.size(), 2u);
  // At heading 0 the rectangle is 0.5 m wide and 0.4 m high: its pixel sides are in that ratio,
  // and the body's centre is the start (the midpoint of opposite corners).
  const auto& b = bodies[0];
  const double w = std::abs(b[0] - b[2]), h = std::abs(b[3] - b[5]);
  EXPECT_NEAR(w / h, 0.5 / 0.4, 0.02);
  EXPECT_GT(w, 10.0);
}

TEST(TrajectorySvg, UnknownMapCellsAreHatchedNotGrey) {
  // A 4 x 2 grid: (0,0) occupied, (1,0) and (2,0) unknown, the rest free.
  std::vector<std::uint8_t> occ(8, 0), unknown(8, 0);
  occ[0] = 1;
  unknown[1] = unknown[2] = 1;
  auto grid = std::make_shared<OccupancyGrid>(4, 2, 0.5, Pose2{}, occ);
  grid->set_unknown(unknown);
  EXPECT_TRUE(grid->unknown(1, 0));
  EXPECT_FALSE(grid->unknown(0, 0));
  EXPECT_FALSE(grid->unknown(-1, 0));
  EXPECT_THROW(grid->set_unknown(std::vector<std::uint8_t>(3, 0)), std::invalid_argument);
  WorldDesc desc;
  desc.grid = grid;
  Scenario s = fleet_of(1);
  s.robots_listed = false;
  s.world = std::make_shared<const World>(std::move(desc));
  const std::string svg = render_trajectory_svg(s, straight_run("r", Vec2(0.2, 0.7), 10));
  // One run of two unknown cells (M1 0h2...), one occupied cell (M0 0h1...), in two paths.
  const std::size_t unknown_path = svg.find("class=\"unknown\"");
  const std::size_t occupied_path = svg.find("class=\"occupied\"");
  ASSERT_NE(unknown_path, std::string::npos);
  ASSERT_NE(occupied_path, std::string::npos);
  const std::string unknown_d =
      svg.substr(unknown_path, svg.find("/>", unknown_path) - unknown_path);
  const std::string occupied_d =
      svg.substr(occupied_path, svg.find("/>", occupied_path) - occupied_path);
  EXPECT_NE(unknown_d.find("url(#unknown-cells)"), std::string::npos);
  EXPECT_NE(unknown_d.find("d=\"M1 0h2v1h-2z\""), std::string::npos);
  EXPECT_NE(occupied_d.find("d=\"M0 0h1v1h-1z\""), std::string::npos);
  EXPECT_EQ(occupied_d.find("M1 0"), std::string::npos);  // unknown is not drawn as occupied
  EXPECT_NE(svg.find(">unknown (map)</text>"), std::string::npos);
}

TEST(TrajectorySvg, AMapWithoutUnknownCellsHasNoHatching) {
  std::vector<std::uint8_t> occ(8, 0);
  occ[0] = 1;
  WorldDesc desc;
  desc.grid = std::make_shared<const OccupancyGrid>(4, 2, 0.5, Pose2{}, occ);
  Scenario s = fleet_of(1);
  s.robots_listed = false;
  s.world = std::make_shared<const World>(std::move(desc));
  const std::string svg = render_trajectory_svg(s, straight_run("r", Vec2(0.2, 0.7), 10));
  EXPECT_EQ(svg.find("unknown"), std::string::npos);
  EXPECT_NE(svg.find("class=\"occupied\""), std::string::npos);
}

}  // namespace
}  // namespace floornav
