// The command-line contract: files written, exit statuses, one clear message for bad input.
#include <gtest/gtest.h>

#include "cli_harness.hpp"

#include <unistd.h>
#include <array>
#include <cstdio>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

namespace fs = std::filesystem;

namespace {
using namespace cli_harness;

fs::path temp_dir(const std::string& name) {
  return fresh_temp_dir("cli_" + name);
}
}  // namespace

TEST(Cli, RunWritesTheThreeFiles) {
  const fs::path out = temp_dir("run");
  const Output o = floornav("run " + scenario("rectangle.yaml") + " --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("rectangle: reached"), std::string::npos) << o.text;
  const auto summary = nlohmann::json::parse(read(out / "summary.json"));
  EXPECT_EQ(summary["scenario"], "rectangle");
  EXPECT_EQ(summary["status"], "reached");
  EXPECT_TRUE(summary["reached_goal"].get<bool>());
  EXPECT_GT(summary["mode_time"].value("follow_boundary_cw", 0.0) +
                summary["mode_time"].value("follow_boundary_ccw", 0.0),
            0.0);
  const std::string csv = read(out / "trajectory.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t,x,y,theta,v,omega,w_left,w_right,mode");
  EXPECT_EQ(read(out / "trajectory.svg").rfind("<svg", 0), 0u);
}

// The chapter's go-to-goal with no obstacle (an empty, unbounded world): it runs, and its
// clearance, which nothing bounds, is null in the JSON files, an empty CSV cell and "none" in the
// text, never infinity, NaN or a made-up number.
TEST(Cli, AnEmptyUnboundedWorldRunsWithNullClearance) {
  const fs::path dir = temp_dir("open_floor");
  fs::create_directories(dir);
  std::ofstream(dir / "open.yaml") << "name: open-floor\nworld: {}\n"
                                      "robot: {preset: quickbot, start: [0, 0, 0]}\n"
                                      "goal: [2, 1]\nsim: {t_max: 30}\n";
  const Output o = floornav("run " + (dir / "open.yaml").string() + " --record clearance --out " +
                            (dir / "run").string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("open-floor: reached"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("min clearance none"), std::string::npos) << o.text;
  const auto summary = nlohmann::json::parse(read(dir / "run" / "summary.json"));
  EXPECT_EQ(summary["status"], "reached");
  ASSERT_TRUE(summary.contains("min_clearance"));
  EXPECT_TRUE(summary["min_clearance"].is_null()) << summary["min_clearance"];
  // trajectory.csv's clearance column: present, and empty on every row.
  std::istringstream csv(read(dir / "run" / "trajectory.csv"));
  std::string header, row;
  std::getline(csv, header);
  ASSERT_EQ(header.substr(header.rfind(',') + 1), "clearance") << header;
  int rows = 0;
  while (std::getline(csv, row)) {
    ++rows;
    ASSERT_EQ(row.back(), ',') << "row " << rows << ": " << row;
  }
  EXPECT_GT(rows, 10);
  const std::string svg = read(dir / "run" / "trajectory.svg");
  EXPECT_NE(svg.find("min clearance none"), std::string::npos);
  for (const char* bad : {"inf", "nan"})
    EXPECT_EQ(read(dir / "run" / "trajectory.csv").find(bad), std::string::npos) << bad;

  // A batch: the case's line and the aggregate carry null as well.
  const Output b = floornav("batch " + (dir / "open.yaml").string() + " --no-timing --out " +
                            (dir / "batch").string());
  ASSERT_EQ(b.status, 0) << b.text;
  const auto line = nlohmann::json::parse(read(dir / "batch" / "results.jsonl"));
  EXPECT_EQ(line["status"], "reached");
  EXPECT_TRUE(line["min_clearance"].is_null()) << line;
  const auto aggregate = nlohmann::json::parse(read(dir / "batch" / "aggregate.json"));
  EXPECT_TRUE(aggregate["min_clearance"].is_null()) << aggregate;
  fs::remove_all(dir);
}

TEST(Cli, SetChangesTheController) {
  const fs::path out = temp_dir("set");
  const Output o = floornav("run " + scenario("rectangle.yaml") +
                            " --set controller.kind=go_to_goal --set controller.safety=off --out " +
                            out.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("collision"), std::string::npos);
}

TEST(Cli, BadInputExitsWithStatus2AndOneMessage) {
  Output o = floornav("run /nonexistent.yaml");
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.text.find("/nonexistent.yaml: does not exist"), std::string::npos) << o.text;
  o = floornav("run " + scenario("rectangle.yaml") + " --set controller.kind=zigzag --out " +
               temp_dir("bad").string());
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.text.find("controller.kind"), std::string::npos) << o.text;
  EXPECT_EQ(std::count(o.text.begin(), o.text.end(), '\n'), 1) << o.text;
  EXPECT_FALSE(fs::exists(temp_dir("bad")));  // nothing written half-way
  o = floornav("run");
  EXPECT_EQ(o.status, 2);
  o = floornav("frobnicate");
  EXPECT_EQ(o.status, 2);
}

TEST(Cli, BatchWritesOrderedResultsIdenticalForAnyJobCount) {
  const std::string files = scenario("rectangle.yaml") + " " + scenario("circle_obstacle.yaml") +
                            " " + scenario("week7_pocket.yaml") + " " +
                            scenario("point_obstacle.yaml");
  const fs::path one = temp_dir("batch1"), two = temp_dir("batch2");
  Output o = floornav("batch " + files + " --no-timing --jobs 1 --out " + one.string());
  ASSERT_EQ(o.status, 0) << o.text;
  o = floornav("batch " + files + " --no-timing --jobs 2 --out " + two.string());
  ASSERT_EQ(o.status, 0) << o.text;
  const std::string a = read(one / "results.jsonl");
  EXPECT_EQ(a, read(two / "results.jsonl"));
  EXPECT_EQ(std::count(a.begin(), a.end(), '\n'), 4);
  EXPECT_EQ(nlohmann::json::parse(a.substr(0, a.find('\n')))["scenario"], "rectangle");
  const auto agg = nlohmann::json::parse(read(one / "aggregate.json"));
  EXPECT_EQ(agg["runs"], 4);
  EXPECT_DOUBLE_EQ(agg["success_rate"].get<double>(), 1.0);
}

// Each .scen row's start and goal are its cells' centres at --cell-size, in every case: the cases
// are made when they run, after the function that read the file has returned (the cell size
// was once read through a dangling reference there, and the poses came out as 1e-318).
TEST(Cli, ScenBatchPlacesEveryRowAtItsCellCentres) {
  const fs::path out = temp_dir("scen_rows");
  const std::string scen =
      std::string(FLOORNAV_TEST_DATA_DIR) + "/maps/movingai-mapf/room-32-32-4-random-1.scen";
  const Output o =
      floornav("batch " + scenario("movingai_template.yaml") + " --scen " + scen +
               " --cell-size 0.5 --limit 3 --no-timing --jobs 1 --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.text;
  std::istringstream lines(read(out / "results.jsonl"));
  // Rows 1-3 (file lines 2-4): start cell, goal cell (x, y from the top, 32 rows), optimum.
  struct Row {
    int sx, sy, gx, gy;
    double optimal;
  };
  const Row rows[] = {
      {21, 14, 9, 0, 23.65685425}, {29, 30, 5, 25, 39.82842712}, {1, 25, 22, 22, 25.89949493}};
  std::string text;
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(std::getline(lines, text)) << "line " << k;
    const auto j = nlohmann::json::parse(text);
    const Row& r = rows[k];
    EXPECT_EQ(j["case"], k);
    EXPECT_EQ(j["source"], scen + ":" + std::to_string(k + 2));
    // (x + 0.5) * 0.5 and (32 - 1 - y + 0.5) * 0.5: row 1 starts at (10.75, 8.75).
    EXPECT_DOUBLE_EQ(j["start"][0].get<double>(), (r.sx + 0.5) * 0.5) << text;
    EXPECT_DOUBLE_EQ(j["start"][1].get<double>(), (31 - r.sy + 0.5) * 0.5) << text;
    EXPECT_DOUBLE_EQ(j["goals"][0][0].get<double>(), (r.gx + 0.5) * 0.5) << text;
    EXPECT_DOUBLE_EQ(j["goals"][0][1].get<double>(), (31 - r.gy + 0.5) * 0.5) << text;
    EXPECT_DOUBLE_EQ(j["optimal_length"].get<double>(), r.optimal * 0.5);
    // Not a collision at the start: the body is placed on free floor.
    EXPECT_GT(j["steps"].get<int>(), 0) << text;
  }
  EXPECT_FALSE(std::getline(lines, text));
}

TEST(Cli, BatchWritesTheGridOptimumAndPathEfficiency) {
  const std::string files = scenario("rectangle.yaml") + " " + scenario("circle_obstacle.yaml");
  const fs::path on = temp_dir("optimum_on"), off = temp_dir("optimum_off");
  ASSERT_EQ(floornav("batch " + files + " --no-timing --out " + on.string()).status, 0);
  const std::string text = read(on / "results.jsonl");
  std::istringstream lines(text);
  std::string l;
  double efficiency_sum = 0.0;
  while (std::getline(lines, l)) {
    const auto j = nlohmann::json::parse(l);
    ASSERT_EQ(j["status"], "reached");
    EXPECT_EQ(j["optimal_source"], "grid_astar");
    const double opt = j["optimal_length"].get<double>(), driven = j["path_length"].get<double>();
    // Reaching the goal needs at least the straight line; octile is never shorter than pulled.
    EXPECT_GT(opt, 2.0);
    EXPECT_GE(j["optimal_octile_length"].get<double>(), opt);
    EXPECT_DOUBLE_EQ(j["path_efficiency"].get<double>(), opt / driven);
    efficiency_sum += opt / driven;
  }
  const auto agg = nlohmann::json::parse(read(on / "aggregate.json"));
  EXPECT_NEAR(agg["mean_path_efficiency_reached"].get<double>(), efficiency_sum / 2.0, 1e-12);
  EXPECT_EQ(agg["runs_with_optimum"], 2);
  EXPECT_EQ(agg["optimal_sources"]["grid_astar"], 2);
  // --no-optimum: no optimum keys at all.
  ASSERT_EQ(floornav("batch " + files + " --no-timing --no-optimum --out " + off.string()).status,
            0);
  EXPECT_EQ(read(off / "results.jsonl").find("optimal"), std::string::npos);
  EXPECT_FALSE(nlohmann::json::parse(read(off / "aggregate.json")).contains("mean_optimal_length"));
}

TEST(Cli, DemoRunsWithNoFiles) {
  const fs::path out = temp_dir("demo");
  const Output o = floornav("demo --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("factory-delivery: reached"), std::string::npos) << o.text;
  EXPECT_TRUE(fs::exists(out / "trajectory.svg"));
}

TEST(Cli, ShardsMergeToTheSameResultsAsOneRun) {
  const std::string files = scenario("rectangle.yaml") + " " + scenario("circle_obstacle.yaml") +
                            " " + scenario("point_obstacle.yaml");
  const fs::path all = temp_dir("all"), s1 = temp_dir("s1"), s2 = temp_dir("s2"),
                 merged = temp_dir("merged");
  ASSERT_EQ(floornav("batch " + files + " --no-timing --out " + all.string()).status, 0);
  ASSERT_EQ(floornav("batch " + files + " --no-timing --shard 1/2 --out " + s1.string()).status, 0);
  ASSERT_EQ(floornav("batch " + files + " --no-timing --shard 2/2 --out " + s2.string()).status, 0);
  const std::string shard1 = read(s1 / "results.jsonl");
  EXPECT_EQ(std::count(shard1.begin(), shard1.end(), '\n'), 2);
  const Output o =
      floornav("merge " + s1.string() + " " + s2.string() + " --out " + merged.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_EQ(read(merged / "results.jsonl"), read(all / "results.jsonl"));
  EXPECT_EQ(read(merged / "aggregate.json"), read(all / "aggregate.json"));
  EXPECT_EQ(floornav("batch " + files + " --shard 3/2").status, 2);
}

TEST(Cli, ResumeCompletesAPartialRunIdentically) {
  const std::string files = scenario("rectangle.yaml") + " " + scenario("circle_obstacle.yaml") +
                            " " + scenario("point_obstacle.yaml");
  const fs::path full = temp_dir("full"), part = temp_dir("part");
  ASSERT_EQ(floornav("batch " + files + " --no-timing --out " + full.string()).status, 0);
  // A partial run (as an interrupted one leaves it): the first case only, then a cut-off line.
  ASSERT_EQ(floornav("batch " + files + " --no-timing --limit 1 --out " + part.string()).status, 0);
  {
    std::ofstream cut(part / "results.jsonl", std::ios::app);
    cut << "{\"case\": 2, \"scen";
  }
  const Output o = floornav("batch " + files + " --no-timing --resume --out " + part.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_EQ(read(part / "results.jsonl"), read(full / "results.jsonl"));
  // The finished case was kept, not run again: only the other two ran.
  EXPECT_NE(o.text.find("3 of 3 cases (1 kept from before, 2 run now)"), std::string::npos)
      << o.text;
  // Resuming a complete folder runs nothing.
  const Output again = floornav("batch " + files + " --no-timing --resume --out " + part.string());
  EXPECT_NE(again.text.find("(3 kept from before, 0 run now)"), std::string::npos) << again.text;
  EXPECT_EQ(read(part / "results.jsonl"), read(full / "results.jsonl"));
  // A folder of another sweep is not resumed into.
  const Output other = floornav("batch " + scenario("rectangle.yaml") +
                                " --no-timing --resume --out " + part.string());
  EXPECT_EQ(other.status, 2) << other.text;
  EXPECT_NE(other.text.find("not shard 1/1 of this sweep"), std::string::npos) << other.text;
}

// Disk full: a 16 KiB tmpfs (needs root; skipped elsewhere). The run fails with exit 1 (an output
// error, not bad input) and one clear message, and results already in the folder stay intact.
TEST(Cli, DiskFullIsAClearErrorAndKeepsEarlierResults) {
  const fs::path mnt = temp_dir("tinyfs");
  fs::create_directories(mnt);
  if (std::system(("mount -t tmpfs -o size=16k tmpfs " + mnt.string() + " 2>/dev/null").c_str()) !=
      0)
    GTEST_SKIP() << "cannot mount a tmpfs here";
  {
    std::ofstream earlier(mnt / "results.jsonl");
    earlier << "{\"case\": 0}\n";
  }
  const Output o =
      floornav("run " + scenario("factory_delivery.yaml") + " --out " + (mnt / "run").string());
  const std::string kept = read(mnt / "results.jsonl");
  const bool left_folder = fs::exists(mnt / "run");
  std::system(("umount " + mnt.string()).c_str());
  // Not the input's fault: status 1 (2 is for bad input), the path and the system's reason.
  EXPECT_EQ(o.status, 1) << o.text;
  EXPECT_NE(o.text.find("/run/"), std::string::npos) << o.text;
  EXPECT_FALSE(left_folder) << "the failed run left its folder";
  EXPECT_NE(o.text.find("No space left on device"), std::string::npos) << o.text;
  EXPECT_EQ(std::count(o.text.begin(), o.text.end(), '\n'), 1) << o.text;
  EXPECT_EQ(kept, "{\"case\": 0}\n");
}

// A fleet scenario through the command line: the contract's three files, the fleet and its robots
// in the summary, a robot column in the CSV, every robot in the picture; --threads gives the
// same summary.
TEST(Cli, RunWritesAFleetsFiles) {
  const fs::path one = temp_dir("fleet1"), two = temp_dir("fleet2");
  const Output o =
      floornav("run " + scenario("fleet_crossing.yaml") + " --threads 1 --out " + one.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("fleet-crossing: 4 robots, 4 reached, 0 collided, 4/4 deliveries"),
            std::string::npos)
      << o.text;
  const auto summary = nlohmann::json::parse(read(one / "summary.json"));
  for (const char* key :
       {"scenario", "status", "reached_goal", "collided", "sim_time", "path_length",
        "min_clearance", "mode_switches", "mode_time", "steps", "wall_time"})
    EXPECT_TRUE(summary.contains(key)) << key;
  EXPECT_EQ(summary["status"], "reached");
  EXPECT_EQ(summary["fleet"]["robots"], 4);
  EXPECT_EQ(summary["fleet"]["deliveries"], 4);
  ASSERT_EQ(summary["robots"].size(), 4u);
  EXPECT_EQ(summary["robots"][0]["scenario"], "east");
  const std::string csv = read(one / "trajectory.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t,x,y,theta,v,omega,w_left,w_right,mode,robot");
  for (const char* name : {",east\n", ",west\n", ",north\n", ",south\n"})
    EXPECT_NE(csv.find(name), std::string::npos) << name;
  const std::string svg = read(one / "trajectory.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find(">south</text>"), std::string::npos);

  ASSERT_EQ(floornav("run " + scenario("fleet_crossing.yaml") + " --threads 2 --quiet --out " +
                     two.string())
                .status,
            0);
  auto a = summary, b = nlohmann::json::parse(read(two / "summary.json"));
  a.erase("wall_time");
  b.erase("wall_time");
  EXPECT_EQ(a, b);
  EXPECT_EQ(csv, read(two / "trajectory.csv"));
}
