// The batch's path-efficiency optimum: cases that share a world search one raster, and each gets
// the optimum scenario_optimum gives it alone.
#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/runner/batch.hpp"
#include "floornav/runner/scenario_optimum.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

namespace fs = std::filesystem;

// Twelve cases on one bounded world (two robot sizes, so the raster changes between some
// consecutive cases), then four on a second world; two workers. Every line's optimum is the one
// of scenario_optimum on that case alone.
TEST(BatchOptimum, CasesSharingAWorldGetEachTheirOwnOptimum) {
  WorldDesc d;
  d.bounds = Box2{{0.0, 0.0}, {4.0, 3.0}};
  d.polygons = {{{1.5, 0.0}, {1.8, 0.0}, {1.8, 1.8}, {1.5, 1.8}},
                {{2.6, 1.2}, {2.9, 1.2}, {2.9, 3.0}, {2.6, 3.0}}};
  const auto first = std::make_shared<const World>(d);
  d.polygons.pop_back();
  const auto second = std::make_shared<const World>(d);
  const RobotPreset quickbot = *find_robot_preset("quickbot");
  const RobotPreset khepera = *find_robot_preset("khepera3");
  Rng rng(3);
  std::vector<BatchCase> cases;
  for (int k = 0; k < 16; ++k) {
    BatchCase c;
    c.id = static_cast<std::size_t>(k);
    c.source = "case" + std::to_string(k);
    c.scenario.name = c.source;
    c.scenario.world = k < 12 ? first : second;
    const RobotPreset& p = k % 5 == 4 ? khepera : quickbot;
    RobotTask& t = c.scenario.robots.emplace_back();
    t.robot = p.robot;
    t.controller.params = p.navigation;
    t.start = {{rng.uniform(0.3, 1.2), rng.uniform(0.3, 2.7)}, 0.0};
    t.goals = {{rng.uniform(3.2, 3.7), rng.uniform(0.3, 2.7)}};
    c.scenario.sim.t_max = 1.0;  // the runs themselves do not matter here
    cases.push_back(std::move(c));
  }
  const fs::path out =
      fs::temp_directory_path() / ("floornav_batch_optimum_" + std::to_string(getpid()));
  BatchOptions o;
  o.jobs = 2;
  o.out_dir = out;
  o.timing = false;
  run_batch(cases, o);
  std::ifstream in(out / "results.jsonl");
  std::string text;
  std::size_t k = 0;
  int found = 0;
  for (; std::getline(in, text); ++k) {
    const auto line = nlohmann::json::parse(text);
    const RobotTask& t = cases[k].scenario.robot();
    const Optimum want =
        scenario_optimum(*cases[k].scenario.world, t.robot.body_radius, t.start.position, t.goals);
    ASSERT_EQ(want.status, OptimumStatus::Found) << k;
    ++found;
    EXPECT_EQ(line["optimal_length"].get<double>(), want.length) << k;
    EXPECT_EQ(line["optimal_octile_length"].get<double>(), want.octile_length) << k;
    EXPECT_EQ(line["optimal_cell_size"].get<double>(), want.cell_size) << k;
  }
  EXPECT_EQ(k, cases.size());
  EXPECT_EQ(found, 16);
  fs::remove_all(out);
}

}  // namespace
}  // namespace floornav
