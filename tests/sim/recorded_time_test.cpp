// Recorded times (trajectory t, sim_time, mode and transition times) are whole numbers of steps,
// written without the drift of adding dt up: a 600 s run ends at 600, not 600.000000000002.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"

using namespace floornav;

namespace {

// A QuickBot in an empty hall, its goal out of reach in t_max: a timeout at exactly t_max.
RunResult long_run(const std::string& dt, const std::string& t_max) {
  const std::string yaml =
      "name: long\nworld: {bounds: [-1, -1, 400, 3]}\n"
      "robot: {preset: quickbot, start: [0, 0, 0]}\ngoal: [399, 0]\n"
      "sim: {dt: " +
      dt + ", t_max: " + t_max + "}\n";
  return simulate(load_scenario_text(yaml, "long.yaml"));
}

}  // namespace

TEST(RecordedTime, SixHundredSecondsAreSixHundred) {
  // Adding 0.01 up 60,000 times drifts: the bug this guards against.
  double sum = 0.0;
  for (int i = 0; i < 60000; ++i) sum += 0.01;
  ASSERT_NE(sum, 600.0);

  const RunResult r = long_run("0.01", "600");
  ASSERT_EQ(r.status, RunStatus::Timeout);
  EXPECT_EQ(r.steps, 60000);
  EXPECT_EQ(r.sim_time, 600.0);
  ASSERT_EQ(r.trajectory.size(), 60001u);
  for (std::size_t k = 0; k < r.trajectory.size(); ++k)
    ASSERT_EQ(r.trajectory[k].t, static_cast<double>(k) / 100.0) << k;
  double total = 0.0;
  for (double m : r.mode_time) {
    EXPECT_EQ(m, std::round(m * 100.0) / 100.0);  // a whole number of centiseconds, exactly
    total += m;
  }
  EXPECT_EQ(total, 600.0);
}

TEST(RecordedTime, AStepThatIsNoWholeFractionOfASecondIsStepsTimesDt) {
  const RunResult r = long_run("0.03", "3");  // 1/dt = 33.3...: t = k * dt
  ASSERT_EQ(r.status, RunStatus::Timeout);
  for (std::size_t k = 0; k < r.trajectory.size(); ++k)
    ASSERT_EQ(r.trajectory[k].t, static_cast<double>(k) * 0.03) << k;
  EXPECT_EQ(r.sim_time, static_cast<double>(r.steps) * 0.03);
}
