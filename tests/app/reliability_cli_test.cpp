// Never crash, never lie, through the command line (docs/RELIABILITY.md): the classes of bad
// input and bad state that issue 37 closed, each checked by what must happen and by what must
// not (no folder left, no line lost, no other sweep's lines kept).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_harness.hpp"

namespace fs = std::filesystem;

namespace {
using namespace cli_harness;

fs::path temp_dir(const std::string& name) {
  return fresh_temp_dir("rel_" + name);
}

void write(const fs::path& p, const std::string& bytes) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << bytes;
}

std::vector<nlohmann::json> lines_of(const fs::path& results) {
  std::vector<nlohmann::json> out;
  std::istringstream in(read(results));
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) out.push_back(nlohmann::json::parse(l));
  return out;
}

/// `p` in single quotes, for the shell.
std::string q(const fs::path& p) {
  std::string out(1, '\'');
  out += p.string();
  out += '\'';
  return out;
}

// Root reads and writes any folder: as root, floornav runs without the two capabilities that let
// it (setpriv, util-linux), so that permissions hold for it as for any other user.
std::string as_any_user() {
  return ::geteuid() == 0 ? "setpriv --bounding-set -dac_override,-dac_read_search --inh-caps=-all"
                          : "";
}

int lines(const std::string& text) {
  return static_cast<int>(std::count(text.begin(), text.end(), '\n'));
}

// A template on a MovingAI map beside it: a 6 x 4 m room, free inside its wall.
const char* kRoomMap = "type octile\nheight 4\nwidth 6\nmap\n@@@@@@\n@....@\n@....@\n@@@@@@\n";
const char* kRoomTemplate =
    "name: room\nworld: {map: room.map, cell_size: 1}\nrobot: {start: [1.5, 1.5, 0]}\n"
    "goal: [4.5, 2.5]\nsim: {t_max: 3}\n";

}  // namespace

// ---- 1: text that is not UTF-8 ----------------------------------------------------------------

// Every way text enters (a name in the file, a --set, a --grid value, a path on the command line)
// gives exit 2 naming the byte, from run, batch and sweep alike: never a writer's exception, an
// abort with threads running, or an output folder.
TEST(Reliability, TextThatIsNotUtf8IsRefusedWhereItEnters) {
  const fs::path dir = temp_dir("utf8");
  write(dir / "bad_name.yaml",
        "name: caf\xe9\nworld: {bounds: [0, 0, 6, 4]}\n"
        "robot: {start: [0.5, 0.5, 0]}\ngoal: [5, 0.5]\n");
  write(dir / "w\xe9.yaml",
        "world: {bounds: [0, 0, 6, 4]}\n"
        "robot: {start: [0.5, 0.5, 0]}\ngoal: [5, 0.5]\n");
  const fs::path out = dir / "out";
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"run " + q(dir / "bad_name.yaml") + " --out " + q(out), "byte 0xe9 is not UTF-8"},
      {"batch " + q(dir / "bad_name.yaml") + " --out " + q(out), "byte 0xe9 is not UTF-8"},
      {"batch " + q(dir / "bad_name.yaml") + " " + scenario("rectangle.yaml") + " --jobs 2 --out " +
           q(out),
       "byte 0xe9 is not UTF-8"},
      {"run " + scenario("rectangle.yaml") + " --set 'name=caf\xe9' --out " + q(out),
       "--set name=caf\\xe9: byte 0xe9 is not UTF-8 (after 'name=caf') (position 9)"},
      {"sweep " + scenario("rectangle.yaml") + " --grid 'name=a,caf\xe9' --out " + q(out),
       "--grid name=a,caf\\xe9: byte 0xe9"},
      {"run " + q(dir / "w\xe9.yaml") + " --out " + q(out), "byte 0xe9"},
      {"batch " + q(dir / "w\xe9.yaml") + " --out " + q(out), "byte 0xe9"},
  };
  for (const auto& [args, needle] : commands) {
    SCOPED_TRACE(args);
    const Output o = floornav(args);
    EXPECT_EQ(o.status, 2) << o.text;
    EXPECT_EQ(lines(o.text), 1) << o.text;
    EXPECT_NE(o.text.find(needle), std::string::npos) << o.text;
    EXPECT_FALSE(fs::exists(out)) << "an output folder was left";
  }
  fs::remove_all(dir);
}

// ---- 3: resume checks that the sweep is the same ----------------------------------------------

// The sweep id covers the files the scenario reads: a map changed between two runs makes another
// sweep, whose folder --resume refuses (its lines were made on the old map).
TEST(Reliability, ResumeRefusesLinesMadeFromAnotherMap) {
  const fs::path dir = temp_dir("resume_map");
  write(dir / "room.map", kRoomMap);
  write(dir / "room.yaml", kRoomTemplate);
  const fs::path out = dir / "out";
  const std::string sweep = "sweep " + q(dir / "room.yaml") +
                            " --grid sim.seed=1,2,3 --no-timing --jobs 1 --out " + q(out);
  Output o = floornav(sweep + " --limit 1");
  ASSERT_EQ(o.status, 0) << o.text;
  // The same map again: resumed.
  o = floornav(sweep + " --resume");
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("1 kept from before, 2 run now"), std::string::npos) << o.text;
  // Another map under the same name: another sweep.
  write(dir / "room.map", "type octile\nheight 4\nwidth 6\nmap\n@@@@@@\n@..@.@\n@....@\n@@@@@@\n");
  const std::string before = read(out / "results.jsonl");
  o = floornav(sweep + " --resume");
  EXPECT_EQ(o.status, 2) << o.text;
  EXPECT_NE(o.text.find("not shard 1/1 of this sweep"), std::string::npos) << o.text;
  EXPECT_EQ(read(out / "results.jsonl"), before);  // untouched
  fs::remove_all(dir);
}

// A folder with results but no sweep.json (Python's batch(out=) wrote such folders) cannot be
// checked: --resume refuses it rather than keep lines of who knows which sweep.
TEST(Reliability, ResumeRefusesAFolderWithoutSweepJson) {
  const fs::path out = temp_dir("resume_nosweep");
  write(out / "results.jsonl",
        "{\"case\": 0, \"source\": \"x\", \"status\": \"reached\", "
        "\"sim_time\": 1.0}\n");
  const Output o = floornav("batch " + scenario("rectangle.yaml") + " --resume --out " + q(out));
  EXPECT_EQ(o.status, 2) << o.text;
  EXPECT_NE(o.text.find("has a results.jsonl but no sweep.json"), std::string::npos) << o.text;
  EXPECT_EQ(lines_of(out / "results.jsonl").size(), 1u);
  fs::remove_all(out);
}

// A line with a case number but no result is not a finished case: resume runs it again. And a
// resume with a smaller --limit never deletes lines already finished.
TEST(Reliability, ResumeRunsLinesWithoutAResultAndKeepsLinesBeyondTheLimit) {
  const fs::path out = temp_dir("resume_lines");
  const std::string sweep = "sweep " + scenario("rectangle.yaml") +
                            " --grid sim.seed=1,2,3,4 --set sim.t_max=2 --no-timing --jobs 1 " +
                            "--out " + q(out);
  Output o = floornav(sweep);
  ASSERT_EQ(o.status, 0) << o.text;
  const std::string complete = read(out / "results.jsonl");
  ASSERT_EQ(lines_of(out / "results.jsonl").size(), 4u);
  // --resume --limit 1 of a finished sweep: nothing runs, nothing is lost.
  o = floornav(sweep + " --resume --limit 1");
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_EQ(read(out / "results.jsonl"), complete);
  EXPECT_EQ(nlohmann::json::parse(read(out / "sweep.json"))["cases"], 4);
  // Case 2's line cut down to its number: run again, and the file ends as it was.
  std::string text = complete;
  std::vector<std::string> rows;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) rows.push_back(l);
  rows[2] = "{\"case\": 2}";
  std::string edited;
  for (const auto& r : rows) edited += r + "\n";
  write(out / "results.jsonl", edited);
  o = floornav(sweep + " --resume");
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_NE(o.text.find("3 kept from before, 1 run now"), std::string::npos) << o.text;
  EXPECT_EQ(read(out / "results.jsonl"), complete);
  // A case given twice: which line is the result? Refused.
  write(out / "results.jsonl", complete + rows[1] + "\n");
  o = floornav(sweep + " --resume");
  EXPECT_EQ(o.status, 2) << o.text;
  EXPECT_NE(o.text.find("case 1 again"), std::string::npos) << o.text;
  fs::remove_all(out);
}

// ---- 5: sources make only the cases --limit and --shard select ---------------------------------

// A case beyond --limit, or in another shard, is never made: a bad value there stops nothing
// (each case is checked before any runs, but only the cases that will run). The sweep id is the
// same for every shard, so the shards still merge.
TEST(Reliability, LimitAndShardMakeOnlyTheCasesTheySelect) {
  const fs::path dir = temp_dir("lazy");
  const std::string sweep = "sweep " + scenario("rectangle.yaml") +
                            " --grid sim.dt=0.01,-1 --set sim.t_max=1 --no-timing --jobs 1";
  Output o = floornav(sweep + " --limit 1 --out " + q(dir / "limit"));
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_EQ(lines_of(dir / "limit" / "results.jsonl").size(), 1u);
  o = floornav(sweep + " --shard 1/2 --out " + q(dir / "s1"));
  ASSERT_EQ(o.status, 0) << o.text;
  // The shard holding the bad case: refused before anything runs, no folder.
  o = floornav(sweep + " --shard 2/2 --out " + q(dir / "s2"));
  EXPECT_EQ(o.status, 2) << o.text;
  EXPECT_NE(o.text.find("sim.dt"), std::string::npos) << o.text;
  EXPECT_FALSE(fs::exists(dir / "s2"));
  // 100000 generated floors, one of them made.
  o = floornav("batch " + scenario("rectangle.yaml") +
               " --floors 100000 --limit 1 --set sim.t_max=1 --no-timing --out " +
               q(dir / "floors"));
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_EQ(lines_of(dir / "floors" / "results.jsonl").size(), 1u);
  fs::remove_all(dir);
}

// ---- 6: paths a source sets are text, never YAML ---------------------------------------------

// A world file whose name holds " #" (a YAML comment) or ": " (a mapping) runs as itself.
TEST(Reliability, WorldPathsWithYamlSyntaxRunAsThemselves) {
  const fs::path dir = temp_dir("paths");
  const std::string box_world =
      "<sdf version='1.6'><world name='w'><model name='box'><static>1</static><pose>2 0 0 0 0 "
      "0</pose><link name='l'><collision name='c'><geometry><box><size>0.4 0.4 1</size></box>"
      "</geometry></collision></link></model></world></sdf>";
  write(dir / "worlds" / "w1.world #2.world", box_world);
  write(dir / "worlds" / "w3: x.world", box_world);
  write(dir / "template.yaml",
        "name: t\nworld: {bounds: [-1, -1, 4, 1]}\nrobot: {start: [0, 0, 0]}\ngoal: [3.5, 0]\n"
        "sim: {t_max: 1}\n");
  const Output o = floornav("batch " + q(dir / "template.yaml") + " --worlds " + q(dir / "worlds") +
                            " --no-timing --out " + q(dir / "out"));
  ASSERT_EQ(o.status, 0) << o.text;
  const auto l = lines_of(dir / "out" / "results.jsonl");
  ASSERT_EQ(l.size(), 2u);
  for (const auto& line : l) {
    const std::string source = line["source"];
    EXPECT_TRUE(source.find("w1.world #2.world") != std::string::npos ||
                source.find("w3: x.world") != std::string::npos)
        << source;
  }
  fs::remove_all(dir);
}

// ---- 7: two --grid on one key -----------------------------------------------------------------

TEST(Reliability, TwoGridsOnOneKeyAreRefused) {
  const fs::path out = temp_dir("grid_twice");
  for (const char* grids : {"--grid sim.seed=1,2 --grid sim.seed=3",
                            "--grid controller=kind=hybrid --grid controller.d_o=0.1,0.2",
                            "--grid goal=[2.4,0] --grid 'goals=[[2.4,0]]'"}) {
    SCOPED_TRACE(grids);
    const Output o = floornav("sweep " + scenario("rectangle.yaml") + " " + std::string(grids) +
                              " --out " + q(out));
    EXPECT_EQ(o.status, 2) << o.text;
    EXPECT_NE(o.text.find("so one would undo the other"), std::string::npos) << o.text;
    EXPECT_FALSE(fs::exists(out));
  }
}

// ---- 15: output folders -----------------------------------------------------------------------

// A run into the folder of an earlier run leaves none of the earlier run's files that it does not
// write itself (a replay, crowd.csv), and keeps files that are not outputs.
TEST(Reliability, ARunIntoAnEarlierRunsFolderLeavesNoStaleFile) {
  const fs::path out = temp_dir("stale");
  Output o = floornav("run " + scenario("crowd/factory_people.yaml") + " --set sim.t_max=1 --out " +
                      q(out));
  ASSERT_EQ(o.status, 0) << o.text;
  ASSERT_TRUE(fs::exists(out / "crowd.csv"));
  ASSERT_TRUE(fs::exists(out / "trajectory.html"));
  write(out / "notes.txt", "mine\n");
  o = floornav("run " + scenario("rectangle.yaml") + " --no-html --out " + q(out));
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_FALSE(fs::exists(out / "crowd.csv"));
  EXPECT_FALSE(fs::exists(out / "trajectory.html"));
  EXPECT_TRUE(fs::exists(out / "summary.json"));
  EXPECT_EQ(read(out / "notes.txt"), "mine\n");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(out)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"notes.txt", "summary.json", "trajectory.csv",
                                             "trajectory.svg", "transitions.csv"}));
  fs::remove_all(out);
}

// Bad input leaves no folder, whichever command and however deep the --out.
TEST(Reliability, BadInputLeavesNoFolder) {
  const fs::path base = temp_dir("no_folder");
  const fs::path out = base / "a" / "b";
  const std::vector<std::string> commands = {
      "run " + scenario("rectangle.yaml") + " --set sim.dt=-1",
      "batch " + scenario("rectangle.yaml") + " --set sim.dt=-1",
      "sweep " + scenario("rectangle.yaml") + " --grid sim.dt=0.01,-1",
      "batch " + scenario("rectangle.yaml") + " --pictures sometimes " + q(base / "pics"),
      "merge " + q(base / "nothing")};
  for (const std::string& args : commands) {
    SCOPED_TRACE(args);
    const Output o = floornav(args + " --out " + q(out));
    EXPECT_EQ(o.status, 2) << o.text;
    EXPECT_FALSE(fs::exists(base)) << "left " << base;
  }
}

// ---- 16: an unreadable --worlds folder ---------------------------------------------------------

TEST(Reliability, AnUnreadableWorldsFolderIsBadInput) {
  const fs::path dir = temp_dir("worlds_unreadable");
  write(dir / "worlds" / "w1.world", "<sdf/>");
  fs::permissions(dir / "worlds", fs::perms::none);
  const Output o = floornav("batch " + scenario("rectangle.yaml") + " --worlds " +
                                q(dir / "worlds") + " --out " + q(dir / "out"),
                            as_any_user());
  fs::permissions(dir / "worlds", fs::perms::owner_all);
  EXPECT_EQ(o.status, 2) << o.text;  // bad input, not an internal error (1)
  EXPECT_EQ(lines(o.text), 1) << o.text;
  EXPECT_NE(
      o.text.find((dir / "worlds").string() + ": cannot be read (--worlds): Permission denied"),
      std::string::npos)
      << o.text;
  EXPECT_FALSE(fs::exists(dir / "out")) << "bad input left a folder";
  fs::remove_all(dir);
}

// ---- 19: messages that blame the right thing ---------------------------------------------------

// A .scen whose map is a ROS map yaml: the map is at fault (its rows are cells of a MovingAI
// grid), not a --cell-size the user never gave.
TEST(Reliability, AScenOnARosMapYamlBlamesTheMapNotTheCellSize) {
  const fs::path dir = temp_dir("scen_ros_yaml");
  write(dir / "room.yaml",
        "image: room.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
        "free_thresh: 0.196\n");
  std::string pgm = "P2\n6 4\n255\n";
  for (int i = 0; i < 24; ++i) pgm += "255 ";
  write(dir / "room.pgm", pgm);
  write(dir / "room.scen", "version 1\n0\troom.yaml\t6\t4\t1\t1\t4\t2\t3.5\n");
  write(dir / "template.yaml", kRoomTemplate);
  write(dir / "room.map", kRoomMap);
  const Output o = floornav("batch " + q(dir / "template.yaml") + " --scen " +
                            q(dir / "room.scen") + " --out " + q(dir / "out"));
  EXPECT_EQ(o.status, 2) << o.text;
  EXPECT_EQ(lines(o.text), 1) << o.text;
  EXPECT_NE(o.text.find("room.scen:line 2 (its map): 'room.yaml' is not a grid a .scen can "
                        "index"),
            std::string::npos)
      << o.text;
  EXPECT_EQ(o.text.find("--cell-size 1"), std::string::npos) << "blamed a default: " << o.text;
  EXPECT_FALSE(fs::exists(dir / "out"));
  // The same row on the MovingAI map runs.
  write(dir / "room.scen", "version 1\n0\troom.map\t6\t4\t1\t1\t4\t2\t3.5\n");
  const Output ok = floornav("batch " + q(dir / "template.yaml") + " --scen " +
                             q(dir / "room.scen") + " --no-timing --out " + q(dir / "out"));
  EXPECT_EQ(ok.status, 0) << ok.text;
  fs::remove_all(dir);
}

// ---- outputs that cannot be written: exit status 1 ---------------------------------------------

// A read-only folder is not bad input: every command that writes files ends with exit status 1
// (2 is for bad input) and one line naming the path it could not write and the system's reason,
// and leaves nothing in the folder.
TEST(Reliability, AReadOnlyOutputIsExitOneNamingThePathAndTheReason) {
  const fs::path dir = temp_dir("read_only");
  const fs::path ro = dir / "ro";
  fs::create_directories(ro);
  const Output shard = floornav("batch " + scenario("rectangle.yaml") + " --no-timing --out " +
                                q(dir / "shard"));  // for merge
  ASSERT_EQ(shard.status, 0) << shard.text;
  fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  struct Case {
    std::string args;
    fs::path named;  ///< the path the message must name
  };
  const std::vector<Case> cases = {
      {"run " + scenario("rectangle.yaml") + " --quiet --out " + q(ro / "run"), ro / "run"},
      {"batch " + scenario("rectangle.yaml") + " --no-timing --out " + q(ro / "batch"),
       ro / "batch"},
      {"merge " + q(dir / "shard") + " --out " + q(ro / "merged"), ro / "merged"},
      {"run " + scenario("rectangle.yaml") + " --quiet --out " + q(dir / "run") + " --config-out " +
           q(ro / "resolved.yaml"),
       ro / "resolved.yaml"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const Output o = floornav(c.args, as_any_user());
    EXPECT_EQ(o.status, 1) << o.text;
    EXPECT_EQ(lines(o.text), 1) << o.text;
    EXPECT_NE(o.text.find("floornav: error: " + c.named.string() + ": "), std::string::npos)
        << o.text;
    EXPECT_NE(o.text.find("Permission denied"), std::string::npos) << o.text;
    EXPECT_TRUE(fs::is_empty(ro)) << "left a file in the read-only folder";
  }
  fs::permissions(ro, fs::perms::owner_all);
  fs::remove_all(dir);
}

// Standard output is an output too: when it cannot be written (a full disk, here /dev/full), the
// command ends with exit status 1 and says so, never status 0 over a cut-off file.
TEST(Reliability, AFullStandardOutputIsExitOne) {
  const fs::path dir = temp_dir("full_stdout");
  for (const std::string& args :
       {std::string("presets"), "run " + scenario("rectangle.yaml") + " --out " + q(dir / "run")}) {
    SCOPED_TRACE(args);
    const Output o = floornav(args, "", "/dev/full");
    EXPECT_EQ(o.status, 1) << o.text;
    EXPECT_EQ(lines(o.text), 1) << o.text;
    EXPECT_NE(
        o.text.find("floornav: error: standard output: cannot write: No space left on device"),
        std::string::npos)
        << o.text;
  }
  // The same commands with somewhere to write: status 0.
  EXPECT_EQ(floornav("presets", "", "/dev/null").status, 0);
  fs::remove_all(dir);
}

// An --out below a file (here the device /dev/full): exit status 1 naming the folder.
TEST(Reliability, AnOutputFolderBelowAFileIsExitOne) {
  const Output o = floornav("run " + scenario("rectangle.yaml") + " --out /dev/full/run");
  EXPECT_EQ(o.status, 1) << o.text;
  EXPECT_EQ(lines(o.text), 1) << o.text;
  EXPECT_NE(o.text.find("/dev/full/run"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("Not a directory"), std::string::npos) << o.text;
}
