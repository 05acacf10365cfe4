// The HTML replay's data: which rows are kept (decimate_track, worked on lines and arcs), what the
// page gets, that big runs stay small, and that no text can end the page's <script> early.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "floornav/render/trajectory_html.hpp"
#include "replay_track.hpp"

namespace floornav {
namespace {

using render_detail::decimate_track;

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// Rows 0.01 s apart of a robot at (x(k), y(k), theta(k)).
template <class F>
std::vector<TrajectorySample> rows_of(int n, F pose) {
  std::vector<TrajectorySample> rows;
  for (int k = 0; k < n; ++k) {
    const auto [x, y, th] = pose(k);
    rows.push_back({0.01 * k, x, y, th, 0.0, 0.0, 0.0, 0.0, 0});
  }
  return rows;
}

/// The largest miss of linear interpolation between kept rows, over every row (m and rad).
std::pair<double, double> worst_miss(const std::vector<TrajectorySample>& rows,
                                     const std::vector<std::size_t>& kept) {
  double pos = 0.0, ang = 0.0;
  for (std::size_t j = 0; j + 1 < kept.size(); ++j) {
    const auto& a = rows[kept[j]];
    const auto& b = rows[kept[j + 1]];
    const double turn = std::remainder(b.theta - a.theta, 2 * std::numbers::pi);
    for (std::size_t i = kept[j]; i <= kept[j + 1]; ++i) {
      const double f =
          static_cast<double>(i - kept[j]) / static_cast<double>(kept[j + 1] - kept[j]);
      pos = std::max(pos, std::hypot(rows[i].x - (a.x + f * (b.x - a.x)),
                                     rows[i].y - (a.y + f * (b.y - a.y))));
      ang = std::max(ang, std::abs(std::remainder(rows[i].theta - (a.theta + f * turn),
                                                  2 * std::numbers::pi)));
    }
  }
  return {pos, ang};
}

TEST(DecimateTrack, AStraightRunAtConstantSpeedKeepsItsEnds) {
  const auto rows = rows_of(3000, [](int k) { return std::tuple{0.003 * k, 1.0, 0.0}; });
  EXPECT_EQ(decimate_track(rows), (std::vector<std::size_t>{0, 2999}));
}

TEST(DecimateTrack, ARunOverTheChunkSizeKeepsTheChunkBoundaries) {
  const auto rows = rows_of(9000, [](int k) { return std::tuple{0.003 * k, 1.0, 0.0}; });
  EXPECT_EQ(decimate_track(rows), (std::vector<std::size_t>{0, 4096, 8192, 8999}));
}

TEST(DecimateTrack, AnArcIsKeptWithinTheTolerance) {
  // Radius 0.5 m at 0.15 m/s (0.3 rad/s): the chord between kept rows may bulge 9 mm, so
  // L^2 / (8 r) <= 0.009 -> chords of up to 0.19 m: about 0.2 rad apart, some 16 rows a turn.
  const auto rows = rows_of(6000, [](int k) {
    const double a = 0.003 * k;
    return std::tuple{0.5 * std::cos(a), 0.5 * std::sin(a), a + std::numbers::pi / 2};
  });
  const auto kept = decimate_track(rows);
  const auto [pos, ang] = worst_miss(rows, kept);
  EXPECT_LE(pos, 0.009);
  EXPECT_LE(ang, 0.01);
  // 18 rad of arc: about 90 kept rows, far fewer than 6,000 (and more than the 18 that a 1 rad
  // chord would need, which would miss by 6 cm).
  EXPECT_GT(kept.size(), 60u);
  EXPECT_LT(kept.size(), 200u);
}

TEST(DecimateTrack, TurningOnTheSpotIsKeptByItsHeading) {
  const auto rows = rows_of(1000, [](int k) { return std::tuple{1.0, 1.0, std::sin(0.01 * k)}; });
  const auto kept = decimate_track(rows);
  EXPECT_LE(worst_miss(rows, kept).second, 0.01);
  EXPECT_GT(kept.size(), 2u);
}

TEST(DecimateTrack, HeadingsAcrossPiAreInterpolatedTheShortWay) {
  // A heading creeping from 3.1 rad up past pi (wrapped to about -3.18 + 2 pi): one straight
  // interpolation covers it, so only the ends are kept.
  const auto rows = rows_of(100, [](int k) {
    return std::tuple{0.0, 0.0, std::remainder(3.1 + 0.001 * k, 2 * std::numbers::pi)};
  });
  EXPECT_EQ(decimate_track(rows), (std::vector<std::size_t>{0, 99}));
}

// ---- the page -----------------------------------------------------------------------------------

/// A robot with five IR sensors wiggling along x for `steps` steps, ranges recorded every step.
RunResult wiggly_run(const std::string& name, int steps, double y0) {
  RunResult r;
  r.scenario = name;
  r.status = RunStatus::Timeout;
  r.mode_names = {"go_to_goal", "follow_boundary_cw", "stop"};
  r.guard_names = {"at_goal"};
  r.mode_time = {0.0, 0.0, 0.0};
  for (int k = 0; k <= steps; ++k) {
    const double t = 0.01 * k;
    const double x = std::fmod(0.15 * t, 18.0), y = y0 + 0.3 * std::sin(0.5 * t);
    r.trajectory.push_back(
        {t, x, y, std::atan2(0.15 * std::cos(0.5 * t), 0.15), 0.15, 0, 0, 0, (k / 700) % 2});
    if (k % 700 == 0 && k > 0) r.transitions.push_back({t, 0, 1, 0});
    r.range_steps.push_back(k);
    for (int i = 0; i < 5; ++i) r.ranges.push_back(i == 2 ? 0.1f + 0.1f * (k % 7) : 0.3f);
  }
  r.steps = steps;
  r.sim_time = 0.01 * steps;
  r.final_x = r.trajectory.back().x;
  r.final_y = r.trajectory.back().y;
  return r;
}

RobotTask quickbot_like(const std::string& name) {
  RobotTask t;
  t.name = name;
  t.robot.body_radius = 0.075;
  for (int i = 0; i < 5; ++i)
    t.robot.sensors.push_back({Pose2{Vec2(0.05, 0.0), (i - 2) * 0.8}, 0.02, 0.3, 0.0, 1});
  t.goals = {Vec2(19.0, 0.0)};
  return t;
}

/// "r<i>" (built by appending: GCC 12 warns, wrongly, on "r" + std::to_string(i) with -Wrestrict).
std::string robot_name(int i) {
  std::string name = "r";
  name += std::to_string(i);
  return name;
}

Scenario hall(int robots) {
  Scenario s;
  s.name = "hall";
  WorldDesc desc;
  desc.bounds = Box2{Vec2(-1.0, -1.0), Vec2(20.0, 20.0)};
  s.world = std::make_shared<const World>(std::move(desc));
  for (int i = 0; i < robots; ++i) s.robots.push_back(quickbot_like(robot_name(i)));
  s.robots_listed = robots > 1;
  return s;
}

TEST(TrajectoryHtml, ATenMinuteRunStaysUnderFiveMegabytes) {
  const Scenario s = hall(1);
  const RunResult r = wiggly_run("wiggle", 60000, 5.0);
  const std::string html = render_trajectory_html(s, r);
  EXPECT_LT(html.size(), 5'000'000u);
  // Every step's 5 ranges would be 300,005 values; the budget keeps 300,000 at most: every 2nd.
  EXPECT_NE(html.find("\"beams\":{\"k\":[0,2,2,2,"), std::string::npos);
  EXPECT_NE(html.find("\"duration\":600"), std::string::npos);
}

TEST(TrajectoryHtml, AHundredRobotTwoMinuteFleetStaysUnderFiveMegabytes) {
  const Scenario s = hall(100);
  FleetResult f;
  f.scenario = "hall";
  for (int i = 0; i < 100; ++i) f.robots.push_back(wiggly_run(robot_name(i), 12000, 0.19 * i));
  const std::string html = render_fleet_html(s, f);
  EXPECT_LT(html.size(), 5'000'000u);
  for (const char* name : {"\"name\":\"r0\"", "\"name\":\"r99\""})
    EXPECT_NE(html.find(name), std::string::npos) << name;
}

TEST(TrajectoryHtml, NoNameCanEndTheScriptEarly) {
  Scenario s = hall(1);
  s.name = "</script><script>alert(1)</script>";
  RunResult r = wiggly_run("</script><img src=x onerror=alert(2)>", 100, 1.0);
  const std::string html = render_trajectory_html(s, r);
  EXPECT_EQ(html.find("<script>alert"), std::string::npos);
  EXPECT_EQ(html.find("<img src=x"), std::string::npos);
  // The page's own three script elements close, nothing else does.
  EXPECT_EQ(count_of(html, "</script>"), 3u);
  // The title is escaped as text.
  EXPECT_NE(html.find("<title>&lt;/script&gt;&lt;script&gt;alert(1)&lt;/script&gt;"),
            std::string::npos);
}

TEST(TrajectoryHtml, AFleetsCrowdIsThinnedToItsBudgetAndKeepsItsLastState) {
  Scenario s = hall(1);
  s.sim.dt = 0.01;
  FleetResult f;
  f.scenario = "hall";
  f.robots.push_back(wiggly_run("r0", 100, 1.0));
  // 30 people and a forklift walking for 10 minutes: 31 x 60,001 = 1,860,031 states; the budget
  // of 200,000 keeps every 10th (ceil(1,860,031 / 200,000)) and the last.
  for (int p = 0; p <= 30; ++p) {
    CrowdTrack t;
    t.name = p < 30 ? robot_name(p) : "fork";
    t.size = p < 30 ? Vec2(0.5, 0.5) : Vec2(1.8, 0.9);
    for (int k = 0; k <= 60000; ++k) t.samples.push_back({0.01 * k, 0.001 * k, 1.0 * p, 0.0});
    (p < 30 ? f.crowd.people : f.crowd.forklifts).push_back(std::move(t));
  }
  f.crowd.metrics.intrusions = 3;
  const std::string html = render_fleet_html(s, f);
  EXPECT_LT(html.size(), 5'000'000u);
  // Rows 0, 10, 20, ... 60000: the last sample (row 60000) is a kept one.
  EXPECT_NE(html.find("\"name\":\"r0\",\"size\":[0.5,0.5],\"track\":{\"k\":[0,10,10,"),
            std::string::npos);
  EXPECT_NE(html.find("\"name\":\"fork\",\"size\":[1.8,0.9]"), std::string::npos);
  EXPECT_NE(html.find("\"intrusions\":3"), std::string::npos);
  // Without people or forklifts the replay says so.
  f.crowd = {};
  EXPECT_NE(render_fleet_html(s, f).find("\"crowd\":null"), std::string::npos);
}

TEST(TrajectoryHtml, ARunWithoutRangesHasNoBeams) {
  RunResult r = wiggly_run("quiet", 100, 1.0);
  r.range_steps.clear();
  r.ranges.clear();
  const std::string html = render_trajectory_html(hall(1), r);
  EXPECT_NE(html.find("\"beams\":null"), std::string::npos);
}

// A run that records its ranges more often than its replay needs (for its bag, run.mcap) draws
// the replay of a run that recorded at the replay's own interval: not the extra frames.
TEST(TrajectoryHtml, ARunRecordingMoreOftenShowsTheFramesOfTheReplaysInterval) {
  Scenario s = hall(1);
  s.sim.t_max = 600.0;  // 60,001 steps x 5 sensors: the replay's interval is 2 steps
  ASSERT_EQ(replay_ranges_interval(s), 2);
  const RunResult every_step = wiggly_run("wiggle", 1000, 5.0);
  RunResult every_2nd = every_step;
  every_2nd.range_steps.clear();
  every_2nd.ranges.clear();
  for (std::size_t f = 0; f < every_step.range_steps.size(); f += 2) {
    every_2nd.range_steps.push_back(every_step.range_steps[f]);
    every_2nd.ranges.insert(every_2nd.ranges.end(), every_step.ranges.begin() + 5 * f,
                            every_step.ranges.begin() + 5 * (f + 1));
  }
  const std::string html = render_trajectory_html(s, every_step);
  EXPECT_EQ(html, render_trajectory_html(s, every_2nd));
  EXPECT_NE(html.find("\"beams\":{\"k\":[0,2,2,2,"), std::string::npos);
  EXPECT_EQ(html.find("\"beams\":{\"k\":[0,1,"), std::string::npos);
}

TEST(ReplayRangesInterval, EveryStepWhenTheBudgetAllowsElseTheFewestStepsApart) {
  Scenario s = hall(1);
  s.sim.dt = 0.01;
  s.sim.t_max = 60.0;  // 6,001 steps x 5 sensors = 30,005 ranges: every step
  EXPECT_EQ(replay_ranges_interval(s), 1);
  s.sim.t_max = 600.0;  // 300,005 ranges: every 2nd step
  EXPECT_EQ(replay_ranges_interval(s), 2);
  Scenario fleet = hall(100);
  fleet.sim.t_max = 120.0;  // 100 x 5 x 12,001 = 6,000,500: every 21st step
  EXPECT_EQ(replay_ranges_interval(fleet), 21);
  fleet.robots.clear();
  EXPECT_EQ(replay_ranges_interval(fleet), 0);
}

}  // namespace
}  // namespace floornav
