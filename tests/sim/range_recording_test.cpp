// Recording the sensor ranges (sim.record_ranges_every, for the HTML replay): which steps are
// recorded, that a frame holds what the robot read at that row's pose, noise included, and that
// recording moves nothing.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sensing/range_sensor.hpp"

using namespace floornav;

namespace {

Scenario rectangle(const std::vector<std::string>& sets) {
  return load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/rectangle.yaml", sets);
}

}  // namespace

TEST(RangeRecording, OffByDefaultAndEveryNthStepWhenOn) {
  const RunResult off = simulate(rectangle({}));
  EXPECT_TRUE(off.range_steps.empty());
  EXPECT_TRUE(off.ranges.empty());

  const Scenario s = rectangle({"sim.record_ranges_every=7"});
  const RunResult on = simulate(s);
  const std::size_t sensors = s.robot().robot.sensors.size();
  ASSERT_GT(sensors, 0u);
  ASSERT_FALSE(on.range_steps.empty());
  EXPECT_EQ(on.ranges.size(), on.range_steps.size() * sensors);
  for (std::size_t k = 0; k < on.range_steps.size(); ++k) EXPECT_EQ(on.range_steps[k], 7 * k);
  EXPECT_LE(on.range_steps.back(), on.steps);
  EXPECT_GT(on.range_steps.back() + 7, on.steps - 1);

  // Recording moves nothing: the same trajectory, bit for bit.
  ASSERT_EQ(on.trajectory.size(), off.trajectory.size());
  for (std::size_t i = 0; i < on.trajectory.size(); ++i) {
    ASSERT_EQ(on.trajectory[i].x, off.trajectory[i].x) << i;
    ASSERT_EQ(on.trajectory[i].theta, off.trajectory[i].theta) << i;
  }
}

// Two intervals (the replay's and the bag's): the steps of either, each once, and no other.
TEST(RangeRecording, ASecondIntervalAddsItsStepsOnly) {
  Scenario s = rectangle({"sim.record_ranges_every=7"});
  s.sim.record_ranges_also_every = 3;
  const RunResult on = simulate(s);
  ASSERT_GT(on.steps, 21);
  std::vector<int> expected;
  for (int k = 0; k <= on.range_steps.back(); ++k)
    if (k % 7 == 0 || k % 3 == 0) expected.push_back(k);
  EXPECT_EQ(on.range_steps, expected);
  EXPECT_EQ(on.ranges.size(), on.range_steps.size() * s.robot().robot.sensors.size());
  EXPECT_GT(on.range_steps.back() + 3, on.steps - 1);
}

TEST(RangeRecording, AFrameIsWhatTheSensorsReadAtThatRowsPose) {
  const Scenario s = rectangle({"sim.record_ranges_every=5"});
  const RunResult r = simulate(s);
  const auto& sensors = s.robot().robot.sensors;
  std::vector<double> expected(sensors.size());
  Rng rng(1);
  std::size_t seen = 0;  // frames in which some sensor saw an obstacle
  for (std::size_t k = 0; k < r.range_steps.size(); ++k) {
    const TrajectorySample& row = r.trajectory[static_cast<std::size_t>(r.range_steps[k])];
    sense_ranges(*s.world, Pose2{Vec2(row.x, row.y), row.theta}, sensors, 0.0, rng, expected);
    bool any = false;
    for (std::size_t i = 0; i < sensors.size(); ++i) {
      ASSERT_EQ(r.ranges[k * sensors.size() + i], static_cast<float>(expected[i])) << k << " " << i;
      any = any || expected[i] < sensors[i].max_range;
    }
    seen += any;
  }
  EXPECT_GT(seen, 10u);  // the robot goes round the rectangle: the frames are not all "nothing"
}

TEST(RangeRecording, NoisySensorsAreRecordedAsTheRobotReadThem) {
  const Scenario s = rectangle({"sim.record_ranges_every=5", "robot.sensors.noise=0.01"});
  const RunResult r = simulate(s);
  const auto& sensors = s.robot().robot.sensors;
  std::vector<double> clean(sensors.size());
  Rng rng(1);
  std::size_t differ = 0;
  for (std::size_t k = 0; k < r.range_steps.size(); ++k) {
    const TrajectorySample& row = r.trajectory[static_cast<std::size_t>(r.range_steps[k])];
    sense_ranges(*s.world, Pose2{Vec2(row.x, row.y), row.theta}, sensors, 0.0, rng, clean);
    for (std::size_t i = 0; i < sensors.size(); ++i)
      if (clean[i] < sensors[i].max_range - 0.05) {
        const double got = r.ranges[k * sensors.size() + i];
        EXPECT_NEAR(got, clean[i], 0.06);  // within 6 sigma of the noise-free range
        differ += got != static_cast<float>(clean[i]);
      }
  }
  EXPECT_GT(differ, 10u);
}

TEST(RangeRecording, ANegativeIntervalIsAnInputError) {
  EXPECT_THROW(rectangle({"sim.record_ranges_every=-1"}), InputError);
}
