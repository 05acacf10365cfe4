// run_batch_case: one case's results.jsonl line, the same as run_batch writes, and what a run
// throws passes through (the Python module builds its batches on it).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "floornav/io/scenario_file.hpp"
#include "floornav/runner/batch.hpp"

namespace floornav {
namespace {

namespace fs = std::filesystem;

std::vector<BatchCase> chapter_cases() {
  std::vector<BatchCase> cases;
  for (const char* name : {"rectangle.yaml", "week7_pocket.yaml", "fleet_crossing.yaml"}) {
    const std::string path = std::string(FLOORNAV_SCENARIO_DIR) + "/" + name;
    cases.push_back({load_scenario_file(path), path, cases.size(), {}, {}, {}});
  }
  return cases;
}

TEST(RunBatchCase, GivesTheLineRunBatchWrites) {
  const auto cases = chapter_cases();
  BatchOptions options;
  options.timing = false;
  options.jobs = 2;
  options.out_dir = fs::temp_directory_path() / ("floornav_batch_case_" + std::to_string(getpid()));
  run_batch(cases, options);
  std::ifstream in(options.out_dir / "results.jsonl");
  std::string text;
  for (const BatchCase& c : cases) {
    ASSERT_TRUE(std::getline(in, text));
    EXPECT_EQ(run_batch_case(c, options).dump(), text) << c.source;
  }
  fs::remove_all(options.out_dir);
}

TEST(RunBatchCase, AControllersExceptionPassesThrough) {
  auto cases = chapter_cases();
  cases[0].scenario.set_controller("throws", make_controller([](const Observation& obs) -> Command {
                                     if (obs.t > 0.1) throw std::runtime_error("controller failed");
                                     return Command::unicycle(0.1, 0.0);
                                   }));
  EXPECT_THROW(run_batch_case(cases[0], BatchOptions{}), std::runtime_error);
}

}  // namespace
}  // namespace floornav
