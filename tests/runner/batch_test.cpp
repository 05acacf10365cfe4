// The batch runner's mechanisms, watched from inside: which cases really run (a controller that
// counts its steps per case), what --resume keeps, what a stop abandons, what merge refuses, and
// that a run's files appear together or not at all.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "floornav/core/input_error.hpp"
#include "floornav/core/output_error.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/io/atomic_file.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/io/trajectory_csv.hpp"
#include "floornav/robot/body_clearance.hpp"
#include "floornav/runner/batch.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/scenario/simulate.hpp"

namespace floornav {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path d =
      fs::temp_directory_path() / ("floornav_batch_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  return d;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<nlohmann::json> lines_of(const fs::path& p) {
  std::vector<nlohmann::json> out;
  std::istringstream in(read(p));
  for (std::string l; std::getline(in, l);) out.push_back(nlohmann::json::parse(l));
  return out;
}

/// The names in a folder, sorted.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

/// Counts, per case, the steps its controller took; a case's controller may also raise `stop`
/// at a given step.
struct StepCounter {
  std::map<std::size_t, std::shared_ptr<std::atomic<long>>> steps;
  std::atomic<bool> stop{false};
  std::map<std::size_t, long> stop_at;  ///< case -> raise `stop` at this step

  std::atomic<long>& of(std::size_t id) {
    auto& p = steps[id];
    if (!p) p = std::make_shared<std::atomic<long>>(0);
    return *p;
  }
};

/// Case `id`: a robot driving straight to a goal 1 m away (about 700 steps), its controller
/// counting into `counter`. `t_max` makes a case long (it then never reaches the goal).
BatchCase counting_case(StepCounter& counter, std::size_t id, double t_max = 60.0,
                        double goal_x = 1.0) {
  BatchCase c;
  c.scenario =
      load_scenario_text("world: {bounds: [-1, -1, " + std::to_string(goal_x + 2.0) +
                             ", 1]}\nrobot: {start: [0, 0, 0]}\ngoal: [" + std::to_string(goal_x) +
                             ", 0]\nsim: {t_max: " + std::to_string(t_max) + "}\n",
                         "counting.yaml");
  std::atomic<long>* steps = &counter.of(id);
  std::atomic<bool>* stop = &counter.stop;
  const long stop_at = counter.stop_at.count(id) ? counter.stop_at[id] : -1;
  c.scenario.set_controller("counting", make_controller([=](const Observation& o) {
                              const long n = ++*steps;
                              if (n == stop_at) stop->store(true);
                              return o.goal_distance() < 0.05 ? Command::goal_reached()
                                                              : Command::unicycle(0.15, 0.0);
                            }));
  c.source = "case" + std::to_string(id);
  c.id = id;
  return c;
}

BatchOptions options_for(const fs::path& dir, StepCounter* counter = nullptr) {
  BatchOptions o;
  o.jobs = 2;
  o.out_dir = dir;
  o.timing = false;
  o.optimum = false;
  o.stop = counter ? &counter->stop : nullptr;
  o.sweep = {"test-sweep", 1, 1, 5};
  return o;
}

// --resume runs only the cases without a line: the finished ones are never simulated again.
TEST(Batch, ResumeRunsOnlyTheUnfinishedCases) {
  const fs::path dir = fresh_dir("resume");
  StepCounter counter;
  std::vector<BatchCase> cases;
  for (std::size_t i = 0; i < 5; ++i) cases.push_back(counting_case(counter, i));
  // A first, partial run: cases 0 and 1 only.
  const auto first = run_batch(std::span(cases).subspan(0, 2), options_for(dir));
  EXPECT_EQ(first.ran, 2u);
  const long steps0 = counter.of(0), steps1 = counter.of(1);
  ASSERT_GT(steps0, 100);
  // Resume the whole sweep: 0 and 1 are kept, 2..4 run.
  BatchOptions o = options_for(dir);
  o.resume = true;
  const auto second = run_batch(cases, o);
  EXPECT_EQ(second.resumed, 2u);
  EXPECT_EQ(second.ran, 3u);
  EXPECT_EQ(counter.of(0), steps0);  // not one more step
  EXPECT_EQ(counter.of(1), steps1);
  for (std::size_t i = 2; i < 5; ++i) EXPECT_EQ(counter.of(i), steps0) << i;  // each ran once
  const auto lines = lines_of(dir / "results.jsonl");
  ASSERT_EQ(lines.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(lines[i]["case"], i);
  EXPECT_EQ(nlohmann::json::parse(read(dir / "aggregate.json"))["runs"], 5);
  // Resuming a complete folder runs nothing at all.
  const auto third = run_batch(cases, o);
  EXPECT_EQ(third.ran, 0u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(counter.of(i), steps0) << i;
  fs::remove_all(dir);
}

// Progress is reported to the caller's callback, never drawn by the runner: from the calling
// thread only (the app's bar is not thread-safe), counts that never go back, resumed cases counted
// as done from the start, and one last report, `finished`, after every case's line is written.
TEST(Batch, ReportsProgressToTheCallbackFromTheCallingThread) {
  const fs::path dir = fresh_dir("progress");
  StepCounter counter;
  std::vector<BatchCase> cases;
  for (std::size_t i = 0; i < 4; ++i) cases.push_back(counting_case(counter, i));
  run_batch(std::span(cases).subspan(0, 1), options_for(dir));
  BatchOptions o = options_for(dir);
  o.resume = true;
  std::vector<BatchProgress> reports;
  std::vector<std::thread::id> threads;
  std::vector<std::size_t> lines_at_finish;
  o.progress = [&](const BatchProgress& p) {
    reports.push_back(p);
    threads.push_back(std::this_thread::get_id());
    if (p.finished) lines_at_finish.push_back(lines_of(dir / "results.jsonl").size());
  };
  const auto outcome = run_batch(cases, o);
  EXPECT_EQ(outcome.ran, 3u);
  ASSERT_GE(reports.size(), 2u);
  for (const std::thread::id& t : threads) EXPECT_EQ(t, std::this_thread::get_id());
  EXPECT_GE(reports.front().done, 1u);  // the resumed case, done before any ran
  for (std::size_t k = 0; k < reports.size(); ++k) {
    EXPECT_EQ(reports[k].total, 4u);
    EXPECT_EQ(reports[k].finished, k + 1 == reports.size()) << k;
    EXPECT_GE(reports[k].elapsed, 0.0);
    if (k > 0) {
      EXPECT_GE(reports[k].done, reports[k - 1].done) << k;
      EXPECT_GE(reports[k].elapsed, reports[k - 1].elapsed) << k;
    }
  }
  EXPECT_EQ(reports.back().done, 4u);
  EXPECT_EQ(lines_at_finish, std::vector<std::size_t>{4u});
  // Without a callback nothing is reported and the files are the same.
  const std::string with = read(dir / "results.jsonl");
  o.progress = nullptr;
  o.resume = false;
  run_batch(cases, o);
  EXPECT_EQ(read(dir / "results.jsonl"), with);
  fs::remove_all(dir);
}

// A resume that is itself interrupted leaves every case once: no duplicate lines, and an
// aggregate that counts what the file holds. A later resume runs only what is still missing.
TEST(Batch, AnInterruptedResumeLeavesNoDuplicates) {
  const fs::path dir = fresh_dir("resume_interrupted");
  StepCounter counter;
  counter.stop_at[3] = 50;  // case 3 raises the stop 50 steps in
  std::vector<BatchCase> cases;
  for (std::size_t i = 0; i < 5; ++i) cases.push_back(counting_case(counter, i));
  run_batch(std::span(cases).subspan(0, 2), options_for(dir));
  BatchOptions o = options_for(dir, &counter);
  o.resume = true;
  o.jobs = 1;
  const auto interrupted = run_batch(cases, o);
  EXPECT_TRUE(interrupted.interrupted);
  const auto lines = lines_of(dir / "results.jsonl");
  std::set<std::size_t> ids;
  for (const auto& l : lines) EXPECT_TRUE(ids.insert(l["case"].get<std::size_t>()).second);
  EXPECT_FALSE(ids.count(3));  // abandoned, not written
  EXPECT_EQ(nlohmann::json::parse(read(dir / "aggregate.json"))["runs"], lines.size());
  EXPECT_EQ(nlohmann::json::parse(read(dir / "aggregate.json"))["complete"], false);
  // Finish it: the cases already written do not run again.
  std::map<std::size_t, long> before;
  for (std::size_t i = 0; i < 5; ++i) before[i] = counter.of(i);
  counter.stop = false;
  counter.stop_at.clear();
  std::vector<BatchCase> again;
  for (std::size_t i = 0; i < 5; ++i) again.push_back(counting_case(counter, i));
  const auto done = run_batch(again, o);
  EXPECT_FALSE(done.interrupted);
  EXPECT_EQ(done.ran, 5u - ids.size());
  for (const std::size_t i : ids) EXPECT_EQ(counter.of(i), before[i]) << "case " << i << " re-ran";
  EXPECT_EQ(lines_of(dir / "results.jsonl").size(), 5u);
  fs::remove_all(dir);
}

// Per-case pictures and bags are outputs like results.jsonl's lines: --resume keeps those of the
// finished cases it keeps (untouched) and removes every other case's (an unfinished case's, a
// case of another sweep's); a fresh batch removes them all. Other files are never touched.
TEST(Batch, ResumeKeepsTheFinishedCasesPicturesAndBagsAndRemovesTheRest) {
  const fs::path dir = fresh_dir("resume_bags");
  StepCounter counter;
  std::vector<BatchCase> cases;
  for (std::size_t i = 0; i < 5; ++i) cases.push_back(counting_case(counter, i));
  BatchOptions o = options_for(dir / "out");
  o.pictures = BatchPictures::All;
  o.pictures_dir = dir / "pics";
  o.mcap = BatchPictures::All;
  o.mcap_dir = dir / "bags";
  run_batch(cases, o);
  ASSERT_EQ(listing(dir / "bags"),
            (std::vector<std::string>{"case-00000-counting.mcap", "case-00001-counting.mcap",
                                      "case-00002-counting.mcap", "case-00003-counting.mcap",
                                      "case-00004-counting.mcap"}));
  ASSERT_EQ(listing(dir / "pics").size(), 10u);
  // As if interrupted after case 1's line (cases 2..4 wrote their files but no line), beside a
  // case of another sweep and files that are not case outputs.
  std::istringstream all(read(dir / "out" / "results.jsonl"));
  std::string first, second;
  std::getline(all, first);
  std::getline(all, second);
  std::ofstream(dir / "out" / "results.jsonl") << first << "\n" << second << "\n";
  std::ofstream(dir / "bags" / "case-00000-counting.mcap") << "kept";
  std::ofstream(dir / "pics" / "case-00001-counting.svg") << "kept";
  for (const char* name : {"case-00042-other.mcap", "case-00042-other.svg", "notes.txt",
                           "case-7-short.mcap", "case-00003.mcap"}) {
    std::ofstream(dir / "bags" / name) << "old";
    std::ofstream(dir / "pics" / name) << "old";
  }
  // Resumed with bags and pictures of the failed cases only: cases 2..4 reach their goals again,
  // so they get none, and the files of their first run must not stay beside their new lines.
  o.resume = true;
  o.pictures = BatchPictures::Failed;
  o.mcap = BatchPictures::Failed;
  const auto resumed = run_batch(cases, o);
  EXPECT_EQ(resumed.resumed, 2u);
  EXPECT_EQ(resumed.ran, 3u);
  EXPECT_EQ(listing(dir / "bags"),
            (std::vector<std::string>{"case-00000-counting.mcap", "case-00001-counting.mcap",
                                      "case-00003.mcap", "case-00042-other.svg",
                                      "case-7-short.mcap", "notes.txt"}));
  EXPECT_EQ(listing(dir / "pics"),
            (std::vector<std::string>{"case-00000-counting.html", "case-00000-counting.svg",
                                      "case-00001-counting.html", "case-00001-counting.svg",
                                      "case-00003.mcap", "case-00042-other.mcap",
                                      "case-7-short.mcap", "notes.txt"}));
  EXPECT_EQ(read(dir / "bags" / "case-00000-counting.mcap"), "kept");  // not written again
  EXPECT_EQ(read(dir / "pics" / "case-00001-counting.svg"), "kept");
  EXPECT_EQ(lines_of(dir / "out" / "results.jsonl").size(), 5u);
  // A fresh batch into the same folders: no earlier case's file stays.
  o.resume = false;
  run_batch(cases, o);
  // (A bag in the pictures' folder, a picture in the bags': not this option's, not touched.)
  EXPECT_EQ(listing(dir / "bags"),
            (std::vector<std::string>{"case-00003.mcap", "case-00042-other.svg",
                                      "case-7-short.mcap", "notes.txt"}));
  EXPECT_EQ(listing(dir / "pics"),
            (std::vector<std::string>{"case-00003.mcap", "case-00042-other.mcap",
                                      "case-7-short.mcap", "notes.txt"}));
  // Shards may share the folders: shard 2/2 removes its own cases' files and those of no case of
  // the sweep, never shard 1's.
  for (const char* name :
       {"case-00000-counting.mcap", "case-00001-counting.mcap", "case-00005-counting.mcap"})
    std::ofstream(dir / "bags" / name) << "old";
  o.out_dir = dir / "shard2";
  o.sweep = {"test-sweep", 2, 2, 5};
  run_batch(std::vector<BatchCase>{cases[1], cases[3]}, o);
  EXPECT_EQ(listing(dir / "bags"),
            (std::vector<std::string>{"case-00000-counting.mcap", "case-00003.mcap",
                                      "case-00042-other.svg", "case-7-short.mcap", "notes.txt"}));
  EXPECT_EQ(read(dir / "bags" / "case-00000-counting.mcap"), "old");
  fs::remove_all(dir);
}

// A stop abandons a running case at once instead of waiting for it: a case of 10^8 steps is
// left after a handful of steps (it would otherwise run them all), and it gets no line.
TEST(Batch, AStopAbandonsARunningCase) {
  const fs::path dir = fresh_dir("stop");
  StepCounter counter;
  counter.stop_at[0] = 1000;
  std::vector<BatchCase> cases{counting_case(counter, 0, 1e6, 50.0)};  // never reached: 1e8 steps
  const auto o = run_batch(cases, options_for(dir, &counter));
  EXPECT_TRUE(o.interrupted);
  EXPECT_EQ(o.completed, 0u);
  EXPECT_LT(counter.of(0), 100'000'000);
  EXPECT_TRUE(read(dir / "results.jsonl").empty());
  fs::remove_all(dir);
}

// run_timed with a stop flag reads it at every step: set during step 1000, the run ends there.
TEST(Batch, RunTimedReadsTheStopFlagEveryStep) {
  StepCounter counter;
  counter.stop_at[0] = 1000;
  const BatchCase c = counting_case(counter, 0, 1e6, 50.0);
  EXPECT_FALSE(run_timed(c.scenario, &counter.stop).has_value());
  EXPECT_EQ(counter.of(0), 1000);
}

/// Runs shard k of n of the 5 counting cases into its own folder.
fs::path run_shard(StepCounter& counter, const std::string& name, int k, int n,
                   const std::string& sweep = "test-sweep") {
  const fs::path dir = fresh_dir(name);
  CaseList list{shard_ids(5, k, n), [&](std::size_t id) { return counting_case(counter, id); }};
  BatchOptions o = options_for(dir);
  o.sweep = {sweep, k, n, 5};
  run_batch(list, o);
  return dir;
}

std::string merge_error(std::vector<fs::path> dirs, const fs::path& out) {
  try {
    merge_batches(dirs, out);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// merge joins the shards of one sweep into exactly one big run's files, and refuses a partial,
// mixed or overlapping set, naming what is wrong; --allow-partial says complete: false.
TEST(Batch, MergeAcceptsOnlyAllShardsOfOneSweep) {
  StepCounter counter;
  const fs::path all = fresh_dir("merge_all");
  {
    std::vector<BatchCase> cases;
    for (std::size_t i = 0; i < 5; ++i) cases.push_back(counting_case(counter, i));
    run_batch(cases, options_for(all));
  }
  const fs::path s1 = run_shard(counter, "s1", 1, 3), s2 = run_shard(counter, "s2", 2, 3),
                 s3 = run_shard(counter, "s3", 3, 3);
  EXPECT_EQ(read(s2 / "results.jsonl").find("\"case\":1,"), 1u);  // shard 2/3 holds cases 1, 4
  const fs::path merged = fresh_dir("merged");
  const MergeOutcome ok = merge_batches(std::vector{s3, s1, s2}, merged);
  EXPECT_TRUE(ok.complete);
  EXPECT_EQ(ok.merged, 5u);
  for (const char* f : {"results.jsonl", "aggregate.json", "sweep.json"})
    EXPECT_EQ(read(merged / f), read(all / f)) << f;

  const fs::path out = fresh_dir("merge_out");
  std::string e = merge_error({s1, s2}, out);
  EXPECT_NE(e.find("shard 3/3 of sweep test-sweep is missing"), std::string::npos) << e;
  EXPECT_FALSE(fs::exists(out));
  e = merge_error({s1, s2, s2}, out);
  EXPECT_NE(e.find("is shard 2/3 again"), std::string::npos) << e;
  const fs::path other = run_shard(counter, "other", 3, 3, "another-sweep");
  e = merge_error({s1, s2, other}, out);
  EXPECT_NE(e.find("mixed sweeps"), std::string::npos) << e;
  const fs::path halves = run_shard(counter, "halves", 2, 2);
  e = merge_error({s1, s2, halves}, out);
  EXPECT_NE(e.find("split two ways"), std::string::npos) << e;
  // A shard that lost its line is incomplete.
  std::ofstream(s3 / "results.jsonl", std::ios::trunc).close();
  e = merge_error({s1, s2, s3}, out);
  EXPECT_NE(e.find("shard 3/3 is incomplete: 1 of its 1 cases are missing (case 2)"),
            std::string::npos)
      << e;
  EXPECT_FALSE(fs::exists(out));
  // --allow-partial merges what there is, and says so.
  const MergeOutcome partial = merge_batches(std::vector{s1, s2}, out, true);
  EXPECT_FALSE(partial.complete);
  EXPECT_EQ(partial.merged, 4u);
  EXPECT_EQ(partial.missing_shards, std::vector<int>{3});
  const auto agg = nlohmann::json::parse(read(out / "aggregate.json"));
  EXPECT_EQ(agg["complete"], false);
  EXPECT_EQ(agg["missing_cases"], 1);
  for (const fs::path& d : {all, s1, s2, s3, merged, out, other, halves}) fs::remove_all(d);
}

// A world with nothing near the robot: no clearance is ever measured; the aggregate says null,
// never 1e+300.
TEST(Batch, AggregateOfNoMeasuredClearanceIsNull) {
  const auto agg = aggregate_results(
      {nlohmann::ordered_json{{"status", "reached"}, {"min_clearance", nullptr}}});
  EXPECT_TRUE(agg["min_clearance"].is_null());
  EXPECT_EQ(aggregate_results({})["min_clearance"], nullptr);
}

// The files of one output folder appear together or not at all.
TEST(OutputFolderTest, AllFilesOrNone) {
  const fs::path dir = fresh_dir("folder");
  {
    OutputFolder out(dir);
    out.write("a.txt", "first\n");
    EXPECT_THROW(out.write("b.txt",
                           [](const std::function<void(std::string_view)>& sink) {
                             sink("half");
                             throw InputError("x", "", "the producer failed");
                           }),
                 InputError);
    // Not committed: nothing appears, not even the folder (it was made for the set).
  }
  EXPECT_FALSE(fs::exists(dir));
  // Into an existing folder: the old files stay as they were until the new set is complete.
  fs::create_directories(dir);
  std::ofstream(dir / "a.txt") << "old\n";
  {
    OutputFolder out(dir);
    out.write("a.txt", "new\n");
    EXPECT_EQ(read(dir / "a.txt"), "old\n");
    out.write("b.txt", "new b\n");
    out.commit();
  }
  EXPECT_EQ(read(dir / "a.txt"), "new\n");
  EXPECT_EQ(read(dir / "b.txt"), "new b\n");
  EXPECT_THROW(OutputFolder(dir / "a.txt"), OutputError);  // a file, not a folder
  fs::remove_all(dir);
}

// Files are staged inside the output folder, never beside it: its parent may be read-only, a
// mount point's, or someone else's, and nothing is written outside --out.
TEST(OutputFolderTest, StagesInsideTheFolderNotItsParent) {
  const fs::path parent = fresh_dir("folder_parent");
  const fs::path dir = parent / "out";
  fs::create_directories(parent);
  std::ofstream(parent / "neighbour.txt") << "mine\n";
  {
    OutputFolder out(dir);
    out.write("a.txt", [&](const std::function<void(std::string_view)>& sink) {
      // While a file is written: the parent holds the folder and nothing else new.
      EXPECT_EQ(listing(parent), (std::vector<std::string>{"neighbour.txt", "out"}));
      std::size_t staging = 0;
      for (const std::string& n : listing(dir)) staging += n.rfind(".floornav-staging", 0) == 0;
      EXPECT_EQ(staging, 1u);
      sink("a\n");
    });
    out.commit();
  }
  EXPECT_EQ(listing(dir), std::vector<std::string>{"a.txt"});  // no staging folder left
  EXPECT_EQ(listing(parent), (std::vector<std::string>{"neighbour.txt", "out"}));
  fs::remove_all(parent);
}

// A set that fails removes every folder it created for itself (and only those): bad input or a
// failed write never leaves an empty folder behind.
TEST(OutputFolderTest, AFailedSetLeavesNoFolderItMade) {
  const fs::path base = fresh_dir("folder_made");
  fs::create_directories(base);
  const fs::path dir = base / "a" / "b" / "c";
  {
    OutputFolder out(dir);
    EXPECT_THROW(out.write("x.txt",
                           [](const std::function<void(std::string_view)>&) {
                             throw InputError("x", "", "fails");
                           }),
                 InputError);
  }
  EXPECT_FALSE(fs::exists(base / "a"));
  EXPECT_TRUE(fs::exists(base));  // it was there before
  fs::remove_all(base);
}

// A run into the folder of an earlier run: the earlier run's files that this one does not write
// (its replay, its crowd.csv) are removed, the user's own files are kept.
TEST(OutputFolderTest, OwnedFilesOfAnEarlierSetDoNotStay) {
  const fs::path dir = fresh_dir("folder_stale");
  fs::create_directories(dir);
  for (const char* name : {"summary.json", "trajectory.html", "crowd.csv", "notes.txt"})
    std::ofstream(dir / name) << "old\n";
  {
    OutputFolder out(dir, {"summary.json", "trajectory.html", "crowd.csv", "trajectory.csv"});
    out.write("summary.json", "new\n");
    EXPECT_TRUE(fs::exists(dir / "trajectory.html"));  // nothing changes before commit
    out.commit();
  }
  EXPECT_EQ(read(dir / "summary.json"), "new\n");
  EXPECT_FALSE(fs::exists(dir / "trajectory.html"));
  EXPECT_FALSE(fs::exists(dir / "crowd.csv"));
  EXPECT_EQ(read(dir / "notes.txt"), "old\n");  // not an output's: never touched
  fs::remove_all(dir);
}

TEST(OutputFolderTest, SafeFileNames) {
  EXPECT_EQ(safe_file_name("rectangle"), "rectangle");
  EXPECT_EQ(safe_file_name("../../etc"), "_._.._etc");
  EXPECT_EQ(safe_file_name("/abs/path"), "_abs_path");
  EXPECT_EQ(safe_file_name(".."), "_.");
  EXPECT_EQ(safe_file_name(""), "_");
  EXPECT_EQ(safe_file_name("a\nb c"), "a_b_c");
  EXPECT_EQ(safe_file_name(std::string(500, 'x')).size(), 120u);
}

// --record's columns hold what the pipeline of Fig 5.12 computed, worked again here from the
// recorded rows: theta_d = atan2(u_y, u_x) (eq. 5.28), the heading error wrapped (eq. 5.14)
// against the heading the step started from, the body's clearance at the row's pose, the goal,
// and each sensor's reading.
TEST(Record, ExtraColumnsHoldWhatTheControllerSawAndAskedFor) {
  Scenario s = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/rectangle.yaml");
  s.sim.record = {true, true, true, true, true};
  const RunResult r = simulate(s);
  const auto& c = r.extra_columns;
  ASSERT_EQ(c.size(), 4u + 2u + 1u + 3u + 5u);
  ASSERT_EQ(r.extra.size(), c.size() * r.trajectory.size());
  auto col = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(c.begin(), c.end(), name) - c.begin());
  };
  auto at = [&](std::size_t row, const std::string& name) {
    return r.extra[row * c.size() + col(name)];
  };
  EXPECT_TRUE(std::isnan(at(0, "u_x")));  // the start: nothing asked yet
  EXPECT_TRUE(std::isnan(at(0, "range_0")));
  std::size_t checked = 0;
  for (std::size_t row = 1; row < r.trajectory.size(); ++row) {
    const double ux = at(row, "u_x"), uy = at(row, "u_y");
    ASSERT_TRUE(std::isfinite(ux)) << row;  // the built-in controllers ask for velocities
    if (std::hypot(ux, uy) > 1e-9) {
      const double theta_d = std::atan2(uy, ux);
      EXPECT_EQ(at(row, "theta_d"), theta_d);
      EXPECT_EQ(at(row, "heading_error"), wrap_angle(theta_d - r.trajectory[row - 1].theta));
      ++checked;
    }
    const TrajectorySample& p = r.trajectory[row];
    EXPECT_EQ(at(row, "clearance"),
              body_clearance(*s.world, s.robot().robot, Pose2{{p.x, p.y}, p.theta}));
    EXPECT_EQ(at(row, "goal_x"), 2.4);
    EXPECT_EQ(at(row, "goal_index"), 0.0);
    for (int k = 0; k < 5; ++k) {
      const double range = at(row, "range_" + std::to_string(k));
      EXPECT_GE(range, 0.04);
      EXPECT_LE(range, 0.3);
    }
  }
  EXPECT_GT(checked, 1000u);
  // The CSV carries them, with the start's empty fields empty.
  const std::string csv = trajectory_to_csv(r);
  EXPECT_NE(csv.find(",range_4\n"), std::string::npos);
  // Off (the default): no extra columns, and the same trajectory bit for bit.
  s.sim.record = {};
  const RunResult plain = simulate(s);
  EXPECT_TRUE(plain.extra_columns.empty());
  EXPECT_TRUE(plain.extra.empty());
  ASSERT_EQ(plain.trajectory.size(), r.trajectory.size());
  EXPECT_EQ(plain.trajectory.back().x, r.trajectory.back().x);
}

}  // namespace
}  // namespace floornav

namespace floornav {
namespace {

/// A folder holding `sweep_json` as its sweep.json and `results` as its results.jsonl.
fs::path forged_shard(const std::string& name, const std::string& sweep_json,
                      const std::string& results) {
  const fs::path dir = fresh_dir(name);
  fs::create_directories(dir);
  std::ofstream(dir / "sweep.json") << sweep_json;
  std::ofstream(dir / "results.jsonl") << results;
  return dir;
}

// merge sizes nothing by what sweep.json claims before it is bounded: a 90-byte file claiming
// 10^12 cases or 2 * 10^9 shards is refused at once (it once allocated gigabytes), and a shard
// of 10^9 cases with 2 lines is reported incomplete without listing its cases.
TEST(BatchState, MergeBoundsSweepJsonBeforeAllocating) {
  const std::string line =
      "{\"case\":0,\"source\":\"x\",\"status\":\"reached\",\"sim_time\":1.0}\n";
  const fs::path out = fresh_dir("merge_forged_out");
  struct Case {
    std::string sweep, needle;
  };
  const std::vector<Case> cases = {
      {R"({"sweep_id":"a","shard":1,"shards":1,"cases":1000000000000})",
       "cases: 1000000000000 is more than the 1000000000 cases a sweep may have"},
      {R"({"sweep_id":"a","shard":1,"shards":2000000000,"cases":5})",
       "shards: 2000000000 is not in [1, 1000000]"},
      {R"({"sweep_id":"a","shard":3,"shards":2,"cases":5})", "shard: 3 is not in [1, shards = 2]"},
      {R"({"sweep_id":"a","shard":1,"shards":1,"cases":-5})", "not a sweep.json"},
      {R"({"sweep_id":"a","shard":1,"shards":1,"cases":1000000000})",
       "shard 1/1 is incomplete: 999999999 of its 1000000000 cases are missing (case 1, 2, 3, 4, "
       "5 and 999999994 more)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.sweep);
    const fs::path dir = forged_shard("merge_forged", c.sweep, line);
    const std::string error = merge_error({dir}, out);
    EXPECT_NE(error.find(c.needle), std::string::npos) << error;
    EXPECT_FALSE(fs::exists(out));
    fs::remove_all(dir);
  }
}

// A case given twice in one results file is refused by merge and by resume (which line is the
// result?), and a line without a result is not a finished case: merge refuses it, resume runs
// the case again.
TEST(BatchState, DuplicateCasesAndLinesWithoutAResult) {
  const std::string sweep = R"({"sweep_id":"a","shard":1,"shards":1,"cases":2})";
  const std::string l0 = "{\"case\":0,\"source\":\"x\",\"status\":\"reached\",\"sim_time\":1.0}\n";
  const std::string l1 = "{\"case\":1,\"source\":\"x\",\"status\":\"timeout\",\"sim_time\":2.0}\n";
  const fs::path out = fresh_dir("merge_dup_out");
  fs::path dir = forged_shard("merge_dup", sweep, l0 + l1 + l0);
  std::string error = merge_error({dir}, out);
  EXPECT_NE(error.find("line 3: case 0 again (also on line 1)"), std::string::npos) << error;
  fs::remove_all(dir);
  dir = forged_shard("merge_noresult", sweep, l0 + "{\"case\":1}\n");
  error = merge_error({dir}, out);
  EXPECT_NE(error.find("line 2: not a finished case's line"), std::string::npos) << error;
  fs::remove_all(dir);
  EXPECT_FALSE(fs::exists(out));
}

// An exception on the thread that writes results.jsonl (here: a name that is not UTF-8, which
// input checks keep out of every file-made scenario but a program can still build) leaves
// run_batch as an exception with every worker joined, never std::terminate with threads running.
TEST(BatchState, AWriterExceptionLeavesNoThreadRunning) {
  const fs::path dir = fresh_dir("writer_throws");
  std::vector<BatchCase> cases;
  for (std::size_t i = 0; i < 6; ++i) {
    BatchCase c;
    c.scenario = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/rectangle.yaml");
    c.scenario.sim.t_max = 0.5;
    c.id = i;
    c.source = i == 2 ? std::string("caf\xe9") : std::string("ok");
    cases.push_back(std::move(c));
  }
  BatchOptions o = options_for(dir);
  o.jobs = 3;
  EXPECT_THROW(run_batch(cases, o), std::exception);  // and the test process is still here
  fs::remove_all(dir);
}

}  // namespace
}  // namespace floornav
