// --mcap on the command line: run writes run.mcap beside the other files without changing them,
// batch --mcap writes a bag per failed (or every) case, and a bag that cannot be written is exit
// status 1 with the path and the system's reason, with no file (or part of one) left under the
// final name. The bags' content is checked by the reference readers (tests/mcap).
#include <gtest/gtest.h>
#include <sys/mount.h>

#include "cli_harness.hpp"

#include <cstdlib>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;

namespace {

using namespace cli_harness;

fs::path temp_dir(const std::string& name) {
  return fresh_temp_dir("mcap_" + name);
}

const std::string kMagic("\x89MCAP0\r\n", 8);

TEST(McapCli, RunWritesTheBagAndLeavesTheOtherFilesAsTheyWere) {
  const fs::path plain = temp_dir("plain"), bag = temp_dir("bag");
  const std::string file = scenario("factory_delivery.yaml");
  ASSERT_EQ(floornav("run " + file + " --quiet --no-optimum --out " + plain.string()).status, 0);
  const Output o = floornav("run " + file + " --quiet --no-optimum --mcap --out " + bag.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_FALSE(fs::exists(plain / "run.mcap"));
  const std::string mcap = read(bag / "run.mcap");
  ASSERT_GT(mcap.size(), 1000u);
  EXPECT_EQ(mcap.substr(0, 8), kMagic);
  EXPECT_EQ(mcap.substr(mcap.size() - 8), kMagic);
  EXPECT_NE(mcap.find("nav_msgs/msg/Odometry"), std::string::npos);
  // Recording for the bag moves nothing: the same trajectory and transitions.
  EXPECT_EQ(read(bag / "trajectory.csv"), read(plain / "trajectory.csv"));
  EXPECT_EQ(read(bag / "transitions.csv"), read(plain / "transitions.csv"));
}

// The same scenario and seed: the same bag, byte for byte (a lone robot, and a fleet with people
// and forklifts on two threads).
TEST(McapCli, TheSameRunWritesTheSameBytes) {
  for (const std::string& run :
       {scenario("factory_delivery.yaml") + " --set sim.t_max=15",
        scenario("crowd/factory_people.yaml") + " --set sim.t_max=10 --threads 2"}) {
    const fs::path a = temp_dir("same_a"), b = temp_dir("same_b");
    ASSERT_EQ(floornav("run " + run + " --quiet --mcap --out " + a.string()).status, 0) << run;
    ASSERT_EQ(floornav("run " + run + " --quiet --mcap --out " + b.string()).status, 0) << run;
    const std::string bag = read(a / "run.mcap");
    ASSERT_GT(bag.size(), 1000u) << run;
    EXPECT_EQ(bag, read(b / "run.mcap")) << run;
  }
}

// A lidar run: the bag wants a scan every 2nd step, the replay every 15th; the replay of a run
// with the bag is the replay of a run without it (not one drawn from the bag's frames).
TEST(McapCli, TheBagLeavesTheReplayAsItWas) {
  const fs::path plain = temp_dir("replay_plain"), bag = temp_dir("replay_bag");
  const std::string file = scenario("ros/depot_1.yaml");
  ASSERT_EQ(floornav("run " + file + " --quiet --no-optimum --out " + plain.string()).status, 0);
  ASSERT_EQ(floornav("run " + file + " --quiet --no-optimum --mcap --out " + bag.string()).status,
            0);
  const std::string html = read(plain / "trajectory.html");
  ASSERT_NE(html.find("\"beams\":{"), std::string::npos);
  EXPECT_EQ(read(bag / "trajectory.html"), html);
  EXPECT_EQ(read(bag / "trajectory.csv"), read(plain / "trajectory.csv"));
}

TEST(McapCli, BatchWritesABagPerFailedCase) {
  const fs::path out = temp_dir("batch"), bags = temp_dir("batch_bags");
  // Hard switching: the rectangle is reached, the week-7 pocket is not.
  const Output o =
      floornav("batch " + scenario("rectangle.yaml") + " " + scenario("week7_pocket.yaml") +
               " --set controller.kind=hard_switch --no-timing --out " + out.string() +
               " --mcap failed " + bags.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_TRUE(fs::exists(bags / "case-00001-week7-pocket.mcap"));
  EXPECT_FALSE(fs::exists(bags / "case-00000-rectangle.mcap"));
  EXPECT_EQ(read(bags / "case-00001-week7-pocket.mcap").substr(0, 8), kMagic);
  const Output bad = floornav("batch " + scenario("rectangle.yaml") + " --out " + out.string() +
                              " --mcap some " + bags.string());
  EXPECT_EQ(bad.status, 2) << bad.text;
  EXPECT_NE(bad.text.find("--mcap"), std::string::npos) << bad.text;
}

/// No file under `dir` whose name contains `part` (a bag, or a temporary file of one).
bool has_file_containing(const fs::path& dir, const std::string& part) {
  if (!fs::exists(dir)) return false;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(part) != std::string::npos) return true;
  return false;
}

// A full disk (a 64 KiB tmpfs): the bag (larger than that) fails part way; exit 1, the path of
// the file that did not fit and the system's reason, and neither the bag nor a piece of it is
// left. The bag is written on its own thread while the other files are: which of them meets the
// full disk first is a race (mostly the bag), so the message may name another file of the run.
TEST(McapCli, ABagThatDoesNotFitIsExitOneAndNoFile) {
  const fs::path mnt = temp_dir("full");
  fs::create_directories(mnt);
  if (::mount("tmpfs", mnt.c_str(), "tmpfs", 0, "size=64k") != 0) {
    // Not root: a folder without write permission stands in for the read-only disk.
    ASSERT_NE(::geteuid(), 0u) << "root could not mount a tmpfs";
    const fs::path locked = mnt / "locked";
    fs::create_directories(locked);
    fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
    const Output o = floornav("run " + scenario("rectangle.yaml") + " --quiet --mcap --out " +
                              (locked / "run").string());
    fs::permissions(locked, fs::perms::owner_all);
    EXPECT_EQ(o.status, 1) << o.text;
    EXPECT_NE(o.text.find("Permission denied"), std::string::npos) << o.text;
    EXPECT_FALSE(has_file_containing(locked, "mcap"));
    return;
  }
  // A short lidar run: its CSV and picture fit, its bag (360 ranges a step) does not.
  const Output o = floornav("run " + scenario("rectangle.yaml") +
                            " --set robot.preset=turtlebot3_burger --set sim.t_max=3 --quiet "
                            "--no-optimum --no-html --mcap --out " +
                            (mnt / "run").string());
  const bool left = has_file_containing(mnt, "mcap");
  ::umount(mnt.c_str());
  EXPECT_EQ(o.status, 1) << o.text;
  EXPECT_NE(o.text.find((mnt / "run").string() + "/"), std::string::npos) << o.text;
  EXPECT_NE(o.text.find("No space left on device"), std::string::npos) << o.text;
  EXPECT_EQ(std::count(o.text.begin(), o.text.end(), '\n'), 1) << o.text;
  EXPECT_FALSE(left);
}

// A read-only folder for batch --mcap: exit 1, naming the bag's path and the reason.
TEST(McapCli, ABatchBagIntoAReadOnlyFolderIsExitOne) {
  const fs::path out = temp_dir("ro_out"), bags = temp_dir("ro_bags");
  fs::create_directories(bags);
  const bool mounted = ::mount("tmpfs", bags.c_str(), "tmpfs", MS_RDONLY, "size=16k") == 0;
  if (!mounted) {
    ASSERT_NE(::geteuid(), 0u) << "root could not mount a read-only tmpfs";
    fs::permissions(bags, fs::perms::owner_read | fs::perms::owner_exec);
  }
  const Output o = floornav("batch " + scenario("rectangle.yaml") + " --no-timing --out " +
                            out.string() + " --mcap all " + bags.string());
  if (mounted)
    ::umount(bags.c_str());
  else
    fs::permissions(bags, fs::perms::owner_all);
  EXPECT_EQ(o.status, 1) << o.text;
  EXPECT_NE(o.text.find((bags / "case-00000-rectangle.mcap").string()), std::string::npos)
      << o.text;
  EXPECT_NE(o.text.find(mounted ? "Read-only file system" : "Permission denied"), std::string::npos)
      << o.text;
  EXPECT_FALSE(has_file_containing(bags, "mcap"));
}

}  // namespace
