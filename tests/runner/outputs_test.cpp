// The run outputs of CONTRACT.md: summary.json, trajectory.csv, trajectory.svg, and the atomic
// file writer they go through.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/core/output_error.hpp"
#include "floornav/io/atomic_file.hpp"
#include "floornav/io/crowd_csv.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/io/trajectory_csv.hpp"
#include "floornav/render/trajectory_html.hpp"
#include "floornav/render/trajectory_svg.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

namespace fs = std::filesystem;

/// Three samples: two in go_to_goal, one in follow_boundary_cw, with the switch at t = 0.02.
RunResult small_run() {
  RunResult r;
  r.scenario = "tiny";
  r.status = RunStatus::Reached;
  r.reached_goal = true;
  r.collided = false;
  r.goals_reached = 1;
  r.goal_count = 1;
  r.sim_time = 0.03;
  r.path_length = 0.25;
  r.min_clearance = 0.081;
  r.mode_switches = 1;
  r.steps = 3;
  r.wall_time = 0.004;
  r.mode_names = {"go_to_goal", "follow_boundary_cw", "follow_boundary_ccw", "stop"};
  r.guard_names = {"at_goal", "obstacle_ahead_cw"};
  r.mode_time = {0.02, 0.01, 0.0, 0.0};
  r.transitions = {Transition{0.02, 0, 1, 1}};
  r.transition_x = {0.1};
  r.transition_y = {0.05};
  r.trajectory = {
      {0.01, 0.0, 0.0, 0.0, 0.15, 0.0, 5.0, 5.0, 0},
      {0.02, 0.1, 0.05, 0.5, 0.15, -1.25, 4.5, 5.5, 0},
      {0.03, 0.25, 0.125, 1.0, 0.1, 0.5, 3.0, 3.5, 1},
  };
  r.final_x = 0.25;
  r.final_y = 0.125;
  r.final_theta = 1.0;
  return r;
}

Scenario small_scenario() {
  Scenario s;
  s.name = "tiny";
  WorldDesc desc;
  desc.bounds = Box2{Vec2(-1.0, -1.0), Vec2(2.0, 1.0)};
  desc.circles.push_back(Circle{Vec2(0.8, 0.2), 0.3});
  s.world = std::make_shared<const World>(std::move(desc));
  s.robots.emplace_back();
  s.robot().start = Pose2{Vec2(0.0, 0.0), 0.0};
  s.robot().goals = {Vec2(1.5, 0.5)};
  s.robot().controller.kind = "hybrid";
  return s;
}

std::vector<std::string> keys_of(const nlohmann::ordered_json& j) {
  std::vector<std::string> keys;
  for (auto it = j.begin(); it != j.end(); ++it) keys.push_back(it.key());
  return keys;
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string read_all(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A fresh empty directory under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    path_ = fs::temp_directory_path() /
            ("floornav-outputs-test-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  const fs::path& path() const { return path_; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_)) names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

// ---- summary.json ----------------------------------------------------------------------------

TEST(SummaryJson, KeysInContractOrderThenExtras) {
  const auto j = summary_to_json(small_run());
  const std::vector<std::string> expected{"scenario",      "status",           "reached_goal",
                                          "collided",      "sim_time",         "path_length",
                                          "min_clearance", "mode_switches",    "mode_time",
                                          "steps",         "wall_time",        "goals_reached",
                                          "goal_count",    "chatter_episodes", "first_chatter_time",
                                          "final_pose",    "wait_time",        "safety_time",
                                          "stuck_cause",   "stuck_with",       "path_irregularity",
                                          "transitions"};
  EXPECT_EQ(keys_of(j), expected);
}

TEST(SummaryJson, Values) {
  const auto j = summary_to_json(small_run());
  EXPECT_EQ(j["scenario"], "tiny");
  EXPECT_EQ(j["status"], "reached");
  EXPECT_EQ(j["reached_goal"], true);
  EXPECT_EQ(j["collided"], false);
  EXPECT_EQ(j["sim_time"].get<double>(), 0.03);
  EXPECT_EQ(j["path_length"].get<double>(), 0.25);
  EXPECT_EQ(j["min_clearance"].get<double>(), 0.081);
  EXPECT_EQ(j["mode_switches"], 1);
  EXPECT_EQ(j["steps"], 3);
  EXPECT_EQ(j["wall_time"].get<double>(), 0.004);
  EXPECT_EQ(j["goals_reached"], 1);
  EXPECT_EQ(j["goal_count"], 1);
  EXPECT_EQ(j["chatter_episodes"], 0);
  EXPECT_TRUE(j["first_chatter_time"].is_null());
  EXPECT_EQ(j["final_pose"].dump(), "[0.25,0.125,1.0]");
  EXPECT_FALSE(j.contains("transitions_truncated"));
}

TEST(SummaryJson, ModeTimeListsOnlyModesThatRan) {
  const auto j = summary_to_json(small_run());
  EXPECT_EQ(j["mode_time"].dump(), R"({"go_to_goal":0.02,"follow_boundary_cw":0.01})");
}

TEST(SummaryJson, TransitionsByName) {
  const auto j = summary_to_json(small_run());
  ASSERT_EQ(j["transitions"].size(), 1u);
  EXPECT_EQ(j["transitions"][0].dump(),
            R"({"t":0.02,"from":"go_to_goal","to":"follow_boundary_cw",)"
            R"("guard":"obstacle_ahead_cw","x":0.1,"y":0.05})");
}

TEST(SummaryJson, ContractExampleShape) {
  RunResult r = small_run();
  r.transitions.clear();
  r.transition_x.clear();
  r.transition_y.clear();
  const std::string text = summary_to_json(r).dump();
  EXPECT_EQ(text.rfind(R"({"scenario":"tiny","status":"reached","reached_goal":true,)"
                       R"("collided":false,"sim_time":0.03,"path_length":0.25,)"
                       R"("min_clearance":0.081,"mode_switches":1,)",
                       0),
            0u)
      << text;
}

TEST(SummaryJson, NonFiniteNumbersBecomeNull) {
  RunResult r = small_run();
  r.sim_time = std::numeric_limits<double>::quiet_NaN();
  r.min_clearance = std::numeric_limits<double>::infinity();
  r.path_length = -std::numeric_limits<double>::infinity();
  r.final_theta = std::numeric_limits<double>::quiet_NaN();
  r.transition_x = {std::numeric_limits<double>::infinity()};
  r.first_chatter_time = std::numeric_limits<double>::quiet_NaN();
  const auto j = summary_to_json(r);
  EXPECT_TRUE(j["sim_time"].is_null());
  EXPECT_TRUE(j["min_clearance"].is_null());
  EXPECT_TRUE(j["path_length"].is_null());
  EXPECT_TRUE(j["final_pose"][2].is_null());
  EXPECT_TRUE(j["transitions"][0]["x"].is_null());
  EXPECT_TRUE(j["first_chatter_time"].is_null());
  const std::string text = j.dump();
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_EQ(text.find("inf"), std::string::npos);
  EXPECT_TRUE(nlohmann::json::accept(text));
}

TEST(SummaryJson, ChatterTimeWhenPresent) {
  RunResult r = small_run();
  r.chatter_episodes = 2;
  r.first_chatter_time = 3.5;
  const auto j = summary_to_json(r);
  EXPECT_EQ(j["chatter_episodes"], 2);
  EXPECT_EQ(j["first_chatter_time"].get<double>(), 3.5);
}

TEST(SummaryJson, TransitionsAreCapped) {
  RunResult r = small_run();
  r.transitions.assign(kSummaryMaxTransitions + 5, Transition{1.0, 0, 1, 1});
  r.transition_x.assign(r.transitions.size(), 0.0);
  r.transition_y.assign(r.transitions.size(), 0.0);
  const auto j = summary_to_json(r);
  EXPECT_EQ(j["transitions"].size(), kSummaryMaxTransitions);
  EXPECT_EQ(j["transitions_truncated"], true);
  EXPECT_EQ(keys_of(j).back(), "transitions_truncated");
}

TEST(SummaryJson, UnknownIndicesGetPlaceholderNames) {
  RunResult r = small_run();
  r.transitions = {Transition{0.5, 7, 0, 9}};
  const auto j = summary_to_json(r);
  EXPECT_EQ(j["transitions"][0]["from"], "mode_7");
  EXPECT_EQ(j["transitions"][0]["guard"], "edge_9");
}

// A mode change that no guard made (dwa's modes, a user's controller giving no guard): null, not
// an invented name.
TEST(SummaryJson, ATransitionWithoutAGuardHasANullGuard) {
  RunResult r = small_run();
  r.transitions = {Transition{0.5, 0, 1, -1}};
  const auto j = summary_to_json(r);
  EXPECT_TRUE(j["transitions"][0]["guard"].is_null());
  EXPECT_EQ(j["transitions"][0]["to"], "follow_boundary_cw");
}

// ---- trajectory.csv --------------------------------------------------------------------------

TEST(TrajectoryCsv, HeaderAndRowsExactly) {
  const std::string csv = trajectory_to_csv(small_run());
  EXPECT_EQ(csv,
            "t,x,y,theta,v,omega,w_left,w_right,mode\n"
            "0.01,0,0,0,0.15,0,5,5,go_to_goal\n"
            "0.02,0.1,0.05,0.5,0.15,-1.25,4.5,5.5,go_to_goal\n"
            "0.03,0.25,0.125,1,0.1,0.5,3,3.5,follow_boundary_cw\n");
}

TEST(TrajectoryCsv, ShortestRoundTripNumbers) {
  RunResult r = small_run();
  r.trajectory.resize(1);
  r.trajectory[0].x = 0.1 + 0.2;  // 0.30000000000000004
  const std::string csv = trajectory_to_csv(r);
  const std::string row = csv.substr(csv.find('\n') + 1);
  EXPECT_EQ(row, "0.01,0.30000000000000004,0,0,0.15,0,5,5,go_to_goal\n");
}

TEST(TrajectoryCsv, EmptyTrajectoryIsJustTheHeader) {
  RunResult r = small_run();
  r.trajectory.clear();
  EXPECT_EQ(trajectory_to_csv(r), "t,x,y,theta,v,omega,w_left,w_right,mode\n");
}

// ---- trajectory.svg --------------------------------------------------------------------------

TEST(TrajectorySvg, WellFormedEnough) {
  const std::string svg = render_trajectory_svg(small_scenario(), small_run());
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(svg.find("nan"), std::string::npos);
  EXPECT_EQ(svg.find("inf"), std::string::npos);
  // Every element that opens a group closes it.
  EXPECT_EQ(count_of(svg, "<g "), count_of(svg, "</g>"));
}

TEST(TrajectorySvg, TitleNamesScenarioControllerAndOutcome) {
  const std::string svg = render_trajectory_svg(small_scenario(), small_run());
  EXPECT_NE(svg.find("tiny — hybrid — reached in 0.03 s"), std::string::npos);
}

TEST(TrajectorySvg, LegendListsOnlyTheModesThatRan) {
  const std::string svg = render_trajectory_svg(small_scenario(), small_run());
  EXPECT_NE(svg.find(">go_to_goal</text>"), std::string::npos);
  EXPECT_NE(svg.find(">follow_boundary_cw</text>"), std::string::npos);
  EXPECT_EQ(svg.find("follow_boundary_ccw"), std::string::npos);
  EXPECT_EQ(svg.find(">stop<"), std::string::npos);
  EXPECT_NE(svg.find(">start</text>"), std::string::npos);
  EXPECT_NE(svg.find(">goal</text>"), std::string::npos);
  EXPECT_NE(svg.find(">mode switch</text>"), std::string::npos);
}

TEST(TrajectorySvg, PathColouredByMode) {
  const std::string svg = render_trajectory_svg(small_scenario(), small_run());
  EXPECT_EQ(count_of(svg, "<polyline stroke=\"#1f77b4\""), 1u);  // go_to_goal, merged
  EXPECT_EQ(count_of(svg, "<polyline stroke=\"#ff7f0e\""), 1u);  // follow_boundary_cw
  EXPECT_EQ(mode_color("avoid_obstacle"), "#d62728");
  EXPECT_EQ(mode_color("blended"), "#9467bd");
  EXPECT_EQ(mode_color("stop"), "#000000");
  EXPECT_NE(mode_color("something_else"), mode_color("go_to_goal"));
}

TEST(TrajectorySvg, EscapesTheScenarioName) {
  Scenario s = small_scenario();
  s.name = "a<b & \"c\"";
  const std::string svg = render_trajectory_svg(s, small_run());
  EXPECT_NE(svg.find("a&lt;b &amp; &quot;c&quot;"), std::string::npos);
  EXPECT_EQ(svg.find("a<b"), std::string::npos);
  EXPECT_EQ(svg.find("& \""), std::string::npos);
}

TEST(TrajectorySvg, CollisionShowsARedBody) {
  RunResult r = small_run();
  r.status = RunStatus::Collision;
  r.collided = true;
  const std::string svg = render_trajectory_svg(small_scenario(), r);
  EXPECT_NE(svg.find("collision in 0.03 s"), std::string::npos);
  EXPECT_NE(svg.find("end (collision)"), std::string::npos);
  EXPECT_NE(svg.find("fill=\"#d62728\""), std::string::npos);
}

TEST(TrajectorySvg, EmptyWorldAndNoTrajectory) {
  Scenario s = small_scenario();
  s.world.reset();
  RunResult r = small_run();
  r.trajectory.clear();
  r.transition_x.clear();
  r.transition_y.clear();
  r.final_x = std::numeric_limits<double>::quiet_NaN();
  const std::string svg = render_trajectory_svg(s, r);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(svg.find("<polyline"), std::string::npos);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(TrajectorySvg, LongRunsAreDecimated) {
  RunResult r = small_run();
  r.trajectory.clear();
  for (int i = 0; i < 200000; ++i) {
    const double t = i * 1e-3;
    r.trajectory.push_back({t, 0.9 * std::cos(t), 0.9 * std::sin(3 * t), 0, 0, 0, 0, 0, i / 50000});
  }
  const std::string svg = render_trajectory_svg(small_scenario(), r);
  EXPECT_LT(svg.size(), 200'000u);
  EXPECT_EQ(count_of(svg, "<polyline"), 4u);
}

// ---- crowd.csv ----------------------------------------------------------------------------------

/// The records of RFC 4180 CSV text: fields split at commas outside quotes, "" for a quote.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        rows.back().back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        rows.back().back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().emplace_back();
    } else if (c == '\n') {
      rows.emplace_back(1);
    } else {
      rows.back().back() += c;
    }
  }
  if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();
  return rows;
}

// A name holding a comma, a quote or a line break stays one field of one row: it cannot forge
// rows or columns (crowd.csv is quoted as trajectory.csv is).
TEST(CrowdCsv, NamesNeverForgeRowsOrColumns) {
  CrowdResult crowd;
  const std::vector<std::string> names = {"plain", "a,b", "say \"hi\"", "two\nlines",
                                          "0,person,evil,1,2,3\n9"};
  for (const std::string& n : names) {
    CrowdTrack t;
    t.name = n;
    t.samples = {{0.0, 1.0, 2.0, 0.5}, {0.1, 1.1, 2.0, 0.5}};
    crowd.people.push_back(t);
  }
  crowd.forklifts.push_back(crowd.people[1]);
  const auto rows = parse_csv(crowd_to_csv(crowd));
  ASSERT_EQ(rows.size(), 1u + 2u * (names.size() + 1));  // the header, then every sample once
  EXPECT_EQ(rows[0], (std::vector<std::string>{"t", "kind", "name", "x", "y", "theta"}));
  for (std::size_t r = 1; r < rows.size(); ++r) {
    ASSERT_EQ(rows[r].size(), 6u) << r;
    const std::size_t track = (r - 1) / 2;
    EXPECT_EQ(rows[r][1], track < names.size() ? "person" : "forklift");
    EXPECT_EQ(rows[r][2], track < names.size() ? names[track] : names[1]);
  }
}

// ---- atomic files ----------------------------------------------------------------------------

// What a run records for its files: the replay's interval, the bag's, and with both the steps of
// each (not their greatest common divisor, which records frames neither takes); the shorter
// alone when it divides the other; a scenario's own record_ranges_every is kept.
TEST(PrepareOutputs, RecordsRangesForTheReplayAndTheBagTogether) {
  const Scenario depot =
      load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/ros/depot_1.yaml");
  const auto every = [&](Scenario s, OutputSelection which) {
    prepare_outputs(s, which);
    return std::pair{s.sim.record_ranges_every, s.sim.record_ranges_also_every};
  };
  // A 360-beam lidar for 12,001 steps: the replay every 15th step, the bag 10 times a second.
  ASSERT_EQ(replay_ranges_interval(depot), 15);
  EXPECT_EQ(every(depot, {.html = true, .mcap = false}), std::pair(15, 0));
  EXPECT_EQ(every(depot, {.html = false, .mcap = true}), std::pair(2, 0));
  EXPECT_EQ(every(depot, {.html = true, .mcap = true}), std::pair(15, 2));
  // 60,001 steps at dt 0.01: the replay's 73 steps and the bag's 10.
  Scenario longer = depot;
  longer.sim.dt = 0.01;
  ASSERT_EQ(replay_ranges_interval(longer), 73);
  EXPECT_EQ(every(longer, {.html = true, .mcap = true}), std::pair(73, 10));
  // The bag's interval divides the replay's: its steps hold the replay's too.
  Scenario divides = depot;
  divides.sim.t_max = 2400.0;  // 48,001 steps: the replay every 58th
  ASSERT_EQ(replay_ranges_interval(divides), 58);
  EXPECT_EQ(every(divides, {.html = true, .mcap = true}), std::pair(2, 0));
  Scenario own = depot;
  own.sim.record_ranges_every = 7;
  EXPECT_EQ(every(own, {.html = true, .mcap = true}), std::pair(7, 0));
  EXPECT_EQ(every(depot, {.html = false, .mcap = false}), std::pair(0, 0));
}

TEST(AtomicFile, WritesAndReplaces) {
  TempDir dir;
  const fs::path file = dir.path() / "summary.json";
  write_file_atomically(file, "first");
  EXPECT_EQ(read_all(file), "first");
  write_file_atomically(file, "second, longer than the first");
  EXPECT_EQ(read_all(file), "second, longer than the first");
  write_file_atomically(file, "");
  EXPECT_EQ(read_all(file), "");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"summary.json"});
}

// An output that cannot be written is an OutputError (the path and the system's reason), never
// an InputError: the command line exits 1 for it, 2 being for bad input.
TEST(AtomicFile, MissingDirectoryIsAnOutputError) {
  const fs::path file = "/proc/floornav-test/x";
  try {
    write_file_atomically(file, "data");
    FAIL() << "expected OutputError";
  } catch (const OutputError& e) {
    EXPECT_EQ(e.file, file.string());
    EXPECT_EQ(e.detail, "cannot write: No such file or directory");
    EXPECT_NE(std::string(e.what()).find("cannot write: "), std::string::npos) << e.what();
  }
}

TEST(AtomicFile, FailedRenameLeavesNoTemporaryFile) {
  TempDir dir;
  // The target is a non-empty directory: the temporary file is written, the rename fails.
  const fs::path target = dir.path() / "occupied";
  fs::create_directories(target / "inside");
  EXPECT_THROW(write_file_atomically(target, "data"), OutputError);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"occupied"});
  // A producer that throws: its exception passes through, and no temporary file stays.
  EXPECT_THROW(write_file_atomically(dir.path() / "f",
                                     [](const std::function<void(std::string_view)>& sink) {
                                       sink("half");
                                       throw std::runtime_error("producer");
                                     }),
               std::runtime_error);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"occupied"});
}

TEST(AtomicFile, EnsureDirectory) {
  TempDir dir;
  const fs::path nested = dir.path() / "a" / "b";
  ensure_directory(nested);
  EXPECT_TRUE(fs::is_directory(nested));
  ensure_directory(nested);  // already there: fine
  write_file_atomically(dir.path() / "file", "x");
  EXPECT_THROW(ensure_directory(dir.path() / "file"), OutputError);
  EXPECT_THROW(ensure_directory("/proc/floornav-test/dir"), OutputError);
}

}  // namespace
}  // namespace floornav
