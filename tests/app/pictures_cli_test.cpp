// The replay and the pictures on the command line: run writes trajectory.html (not with
// --no-html), batch --pictures draws the failed (or all) cases without changing any result.
#include <gtest/gtest.h>

#include "cli_harness.hpp"

#include <unistd.h>
#include <array>
#include <cstdio>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace {

using namespace cli_harness;

fs::path temp_dir(const std::string& name) {
  return fresh_temp_dir("pictures_" + name);
}

}  // namespace

TEST(ReplayCli, RunWritesTheReplayBesideTheSvg) {
  const fs::path out = temp_dir("run");
  const Output o = floornav("run " + scenario("rectangle.yaml") + " --quiet --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.text;
  const std::string html = read(out / "trajectory.html");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(html.find("window.floornavReplay"), std::string::npos);
  EXPECT_NE(html.find("\"format\":\"floornav-replay\""), std::string::npos);
  // Self-contained: no script, style or image from anywhere else.
  EXPECT_EQ(html.find("src=\"http"), std::string::npos);
  EXPECT_EQ(html.find("href=\"http"), std::string::npos);
  EXPECT_EQ(html.find("<script src"), std::string::npos);
  // The beams were recorded for it: a frame per step for this short run.
  EXPECT_NE(html.find("\"beams\":{\"k\":[0,1,1,1"), std::string::npos);
}

TEST(ReplayCli, NoHtmlWritesNoReplay) {
  const fs::path out = temp_dir("nohtml");
  const Output o =
      floornav("run " + scenario("rectangle.yaml") + " --quiet --no-html --out " + out.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_TRUE(fs::exists(out / "trajectory.svg"));
  EXPECT_FALSE(fs::exists(out / "trajectory.html"));
}

TEST(ReplayCli, BatchPicturesOfTheFailedCasesOnlyAndTheSameResults) {
  const fs::path plain = temp_dir("batch_plain");
  const fs::path drawn = temp_dir("batch_drawn");
  const fs::path pictures = temp_dir("batch_pictures");
  // Hard switching: the rectangle is reached, the week-7 pocket is not.
  const std::string files = scenario("rectangle.yaml") + " " + scenario("week7_pocket.yaml") +
                            " --set controller.kind=hard_switch --no-timing";
  ASSERT_EQ(floornav("batch " + files + " --out " + plain.string()).status, 0);
  const Output o = floornav("batch " + files + " --out " + drawn.string() + " --pictures failed " +
                            pictures.string());
  ASSERT_EQ(o.status, 0) << o.text;
  EXPECT_EQ(read(plain / "results.jsonl"), read(drawn / "results.jsonl"));
  EXPECT_TRUE(fs::exists(pictures / "case-00001-week7-pocket.svg"));
  EXPECT_TRUE(fs::exists(pictures / "case-00001-week7-pocket.html"));
  EXPECT_FALSE(fs::exists(pictures / "case-00000-rectangle.svg"));

  const fs::path all = temp_dir("batch_all");
  ASSERT_EQ(
      floornav("batch " + files + " --out " + drawn.string() + " --pictures all " + all.string())
          .status,
      0);
  EXPECT_TRUE(fs::exists(all / "case-00000-rectangle.html"));
  EXPECT_TRUE(fs::exists(all / "case-00001-week7-pocket.html"));
}

TEST(ReplayCli, PicturesTakeFailedOrAll) {
  const Output o = floornav("batch " + scenario("rectangle.yaml") + " --pictures some " +
                            temp_dir("bad").string());
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.text.find("--pictures: expected failed or all, got 'some'"), std::string::npos)
      << o.text;
}
