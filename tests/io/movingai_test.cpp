#include "floornav/io/movingai_map.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "floornav/core/input_error.hpp"
#include "support/loader_test_support.hpp"

namespace floornav {
namespace {

namespace fs = std::filesystem;

class MovingAiTest : public test::TempDirTest {};

using test::expect_input_error;

const std::string kTinyMap = "type octile\nheight 3\nwidth 4\nmap\n.@..\nG.TS\n..W.\n";

TEST_F(MovingAiTest, TinyMapFlipsRowsAndKnowsTheTerrain) {
  for (const std::string& text : {kTinyMap, std::string("type octile\r\nheight 3\r\nwidth 4\r\n"
                                                        "map\r\n.@..\r\nG.TS\r\n..W.\r\n")}) {
    const OccupancyGrid g = load_movingai_map(write("t.map", text), 0.5);
    ASSERT_EQ(g.width(), 4);
    ASSERT_EQ(g.height(), 3);
    EXPECT_EQ(g.resolution(), 0.5);
    EXPECT_EQ(g.origin().position, Vec2(0.0, 0.0));
    EXPECT_EQ(g.occupied_count(), 3u);
    EXPECT_TRUE(g.occupied(1, 2));   // '@' in the top row
    EXPECT_TRUE(g.occupied(2, 1));   // 'T'
    EXPECT_TRUE(g.occupied(2, 0));   // 'W' in the bottom row
    EXPECT_FALSE(g.occupied(0, 1));  // 'G'
    EXPECT_FALSE(g.occupied(3, 1));  // 'S' (swamp) is passable
  }
}

TEST_F(MovingAiTest, CellCentre) {
  // Cell (x = 1, y = 0) is the '@' in the top row: centre (0.75, 1.25) with 0.5 m cells.
  EXPECT_EQ(movingai_cell_center(1, 0, 3, 0.5), Vec2(0.75, 1.25));
  EXPECT_EQ(movingai_cell_center(0, 2, 3, 0.5), Vec2(0.25, 0.25));
  const OccupancyGrid g = load_movingai_map(write("t.map", kTinyMap), 0.5);
  EXPECT_LT(g.clearance(movingai_cell_center(1, 0, 3, 0.5)), 0.0);
  EXPECT_GT(g.clearance(movingai_cell_center(0, 0, 3, 0.5)), 0.0);
}

TEST_F(MovingAiTest, BadMaps) {
  struct Case {
    std::string text;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {"", "empty file"},
      {"type tile\nheight 1\nwidth 1\nmap\n.\n", "line 1: unsupported map type 'tile'"},
      {"octile\n", "line 1: expected 'type octile'"},
      {"type octile\nheight x\nwidth 1\nmap\n.\n", "line 2: height must be a positive integer"},
      {"type octile\nheight 1\nheight 1\nmap\n.\n", "line 3: 'height' given twice"},
      {"type octile\nheight 1\nlength 1\nmap\n.\n", "line 3: expected 'height H' or 'width W'"},
      {"type octile\nheight 1\nwidth 1\nmop\n.\n", "line 4: expected 'map'"},
      {"type octile\nheight 2\nwidth 3\nmap\n...\n..\n", "line 6: map row 1 has 2 characters"},
      {"type octile\nheight 3\nwidth 1\nmap\n.\n.\n", "file ends after 2 of 3 map rows"},
      {"type octile\nheight 1\nwidth 1\nmap\n.\n.\n", "line 6: more map rows than the height"},
      {"type octile\nheight 100000\nwidth 100000\nmap\n", "too large"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const fs::path p = write("bad.map", cases[i].text);
    expect_input_error([&] { load_movingai_map(p, 1.0); }, cases[i].needle);
  }
  const fs::path ok = write("ok.map", kTinyMap);
  expect_input_error([&] { load_movingai_map(ok, 0.0); }, "cell_size");
  expect_input_error([&] { load_movingai_map(ok, std::nan("")); }, "cell_size");
  expect_input_error([&] { load_movingai_map(dir_ / "none.map", 1.0); }, "does not exist");
}

TEST_F(MovingAiTest, TinyScen) {
  const fs::path p = write("t.scen",
                           "version 1.0\n"
                           "0\tt.map\t4\t3\t0\t0\t3\t2\t3.82842712\n"
                           "\n"
                           "1\tt.map\t4\t3\t3\t0\t0\t2\t4.5\r\n"
                           "0\tt.map\t4\t3\t1\t1\t1\t1\t0\n");  // start = goal: length 0
  const auto cases = load_movingai_scen(p);
  ASSERT_EQ(cases.size(), 3u);
  EXPECT_EQ(cases[2].optimal_length, 0.0);
  EXPECT_EQ(cases[0].bucket, 0);
  EXPECT_EQ(cases[0].map_file, "t.map");
  EXPECT_EQ(cases[0].width, 4);
  EXPECT_EQ(cases[0].height, 3);
  EXPECT_EQ(cases[0].goal_x, 3);
  EXPECT_EQ(cases[0].goal_y, 2);
  EXPECT_DOUBLE_EQ(cases[0].optimal_length, 3.82842712);
  EXPECT_EQ(cases[1].start_x, 3);
  EXPECT_DOUBLE_EQ(cases[1].optimal_length, 4.5);
}

TEST_F(MovingAiTest, BadScen) {
  const std::string ok = "0\tt.map\t4\t3\t0\t0\t3\t2\t3.82842712\n";
  struct Case {
    std::string text;
    std::string needle;
  };
  const std::vector<Case> cases = {
      {"", "empty file"},
      {"version 2\n" + ok, "line 1: expected 'version 1' or 'version 1.0'"},
      {"version 1\n" + ok + "0\tt.map\t4\t3\t0\t0\t3\t2\n", "line 3: expected 9 tab-separated"},
      {"version 1\n0 t.map 4 3 0 0 3 2 3.5\n", "line 2: expected 9 tab-separated fields, got 1"},
      {"version 1\nx\tt.map\t4\t3\t0\t0\t3\t2\t3.5\n", "line 2: bucket must be an integer"},
      {"version 1\n0\tt.map\t4\t3\t4\t0\t3\t2\t3.5\n",
       "line 2: start x must be an integer in [0, 3]"},
      {"version 1\n0\tt.map\t4\t3\t0\t-1\t3\t2\t3.5\n", "start y"},
      {"version 1\n0\tt.map\t0\t3\t0\t0\t3\t2\t3.5\n", "map width"},
      {"version 1\n0\tt.map\t4\t3\t0\t0\t3\t2\tfar\n", "line 2: optimal length"},
      {"version 1\n0\tt.map\t4\t3\t0\t0\t3\t2\tnan\n", "optimal length"},
      {"version 1\n0\t\t4\t3\t0\t0\t3\t2\t1\n", "map file name is empty"},
      // Optima that are no path's length: 0 between two cells, or below the straight line.
      {"version 1\n0\tt.map\t4\t3\t0\t0\t3\t2\t0\n", "shorter than the straight line"},
      {"version 1\n0\tt.map\t4\t3\t0\t0\t3\t2\t3.6\n", "line 2: optimal length '3.6'"},
      {"version 1\n0\tt.map\t4\t3\t0\t0\t0\t1\t1e-9\n", "shorter than the straight line"},
      // A map name that is not UTF-8 (it is written to JSON as the case's source).
      {"version 1\n0\tt\xe9.map\t4\t3\t0\t0\t3\t2\t3.9\n", "byte 0xe9 is not UTF-8"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const fs::path p = write("bad.scen", cases[i].text);
    expect_input_error([&] { load_movingai_scen(p); }, cases[i].needle);
  }
}

fs::path shared_maps() {
  return fs::path(FLOORNAV_TEST_DATA_DIR) / "maps" / "movingai-mapf";  // copies: SOURCES.md
}

TEST(MovingAiRealFiles, Room32) {
  const OccupancyGrid g = load_movingai_map(shared_maps() / "room-32-32-4.map", 1.0);
  EXPECT_EQ(g.width(), 32);
  EXPECT_EQ(g.height(), 32);
  // The first map row is "@@@.@.@@@.@@@.@@@.@@@.@@@.@@@.@@": free at x = 3 and 5.
  EXPECT_TRUE(g.occupied(0, 31));
  EXPECT_FALSE(g.occupied(3, 31));
  EXPECT_FALSE(g.occupied(5, 31));

  const auto cases = load_movingai_scen(shared_maps() / "room-32-32-4-random-1.scen");
  ASSERT_EQ(cases.size(), 341u);
  // First line: 5 room-32-32-4.map 32 32 21 14 9 0 23.65685425
  EXPECT_EQ(cases[0].bucket, 5);
  EXPECT_EQ(cases[0].map_file, "room-32-32-4.map");
  EXPECT_EQ(cases[0].start_x, 21);
  EXPECT_EQ(cases[0].start_y, 14);
  EXPECT_EQ(cases[0].goal_x, 9);
  EXPECT_EQ(cases[0].goal_y, 0);
  EXPECT_DOUBLE_EQ(cases[0].optimal_length, 23.65685425);
  for (const auto& c : cases) {
    EXPECT_EQ(c.width, 32);
    EXPECT_EQ(c.bucket, static_cast<int>(std::floor(c.optimal_length / 4.0)));
    // Starts and goals are on free cells.
    EXPECT_GT(g.clearance(movingai_cell_center(c.start_x, c.start_y, c.height, 1.0)), 0.0);
    EXPECT_GT(g.clearance(movingai_cell_center(c.goal_x, c.goal_y, c.height, 1.0)), 0.0);
  }
}

TEST(MovingAiRealFiles, AllMapsLoad) {
  const OccupancyGrid den = load_movingai_map(shared_maps() / "den520d.map", 0.25);
  EXPECT_EQ(den.height(), 257);
  EXPECT_EQ(den.width(), 256);
  const OccupancyGrid wh = load_movingai_map(shared_maps() / "warehouse-10-20-10-2-1.map", 1.0);
  EXPECT_EQ(wh.height(), 63);
  EXPECT_EQ(wh.width(), 161);
  EXPECT_EQ(wh.occupied_count(), 4444u);  // 'T' count from SOURCES.md
}

}  // namespace
}  // namespace floornav
