// Simulation::step for the standard robots, and whole scenario runs. items_per_second is
// robot-steps/s; `rays` is ray casts per second. A run that ends (goal reached, stuck, ...) is
// restarted with the timer paused, so every timed iteration is one real step.
//
//   floornav_bench --benchmark_filter='BM_Step|BM_Run|BM_Fleet'
//
// The generated floors come from app/bench_cases.cpp (fixed seeds), shared with `floornav bench`.

#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bench_cases.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/simulation.hpp"

namespace floornav {
namespace {

std::shared_ptr<const World> floor_world(int edges) {
  static std::map<int, std::shared_ptr<const World>> cache;
  auto& w = cache[edges];
  if (!w) {
    const FactoryFloorParams p = edges > 0 ? factory_floor_with_edges(edges) : FactoryFloorParams{};
    w = std::make_shared<const World>(make_factory_floor(p));
  }
  return w;
}

double rays_per_step(const Scenario& s) {
  double n = 0.0;
  for (const RangeSensorSpec& r : s.robot().robot.sensors)
    n += (r.cone_rays > 1 && r.cone_angle > 0.0) ? r.cone_rays : 1;
  return n;
}

/// Steps one robot of `s` per iteration.
void step_robot(benchmark::State& state, const Scenario& s) {
  std::optional<Simulation> sim(std::in_place, *s.world, s.robot(), s.sim, s.name);
  std::int64_t restarts = 0;
  for (auto _ : state) {
    if (!sim->step()) {
      state.PauseTiming();
      sim.emplace(*s.world, s.robot(), s.sim, s.name);
      ++restarts;
      state.ResumeTiming();
    }
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["rays"] = benchmark::Counter(
      rays_per_step(s) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["restarts"] = static_cast<double>(restarts);
}

const Scenario& quickbot_floor() {
  static const Scenario s = make_factory_floor_scenario(floor_world(0), 0);
  return s;
}
const Scenario& lidar180_floor() {
  static const Scenario s = make_factory_floor_scenario(floor_world(0), 180);
  return s;
}

void BM_Step_QuickBot5Ir_50Polygons(benchmark::State& state) {
  step_robot(state, quickbot_floor());
}
BENCHMARK(BM_Step_QuickBot5Ir_50Polygons);

// The planning layer on the same floor: octile A* on the known floor plan, string-pulled, a
// subgoal for the automaton; its plans (one per goal of the tour, and the raster at each
// restart) are inside the timing, amortised over the run.
const Scenario& quickbot_floor_planner() {
  static const Scenario s = [] {
    Scenario p = make_factory_floor_scenario(floor_world(0), 0);
    p.robot().controller.planner.kind = PlannerKind::AStar;
    p.robot().controller.planner.cell_size = 0.1;  // 200 x 200 planning cells
    return p;
  }();
  return s;
}
void BM_Step_QuickBot5Ir_50Polygons_Planner(benchmark::State& state) {
  const Scenario& s = quickbot_floor_planner();
  std::optional<Simulation> sim(std::in_place, *s.world, s.robot(), s.sim, s.name);
  std::int64_t restarts = 0;
  for (auto _ : state)
    if (!sim->step()) {  // the restart (a new planner, its raster) is timed too
      sim.emplace(*s.world, s.robot(), s.sim, s.name);
      ++restarts;
    }
  state.SetItemsProcessed(state.iterations());
  state.counters["restarts"] = static_cast<double>(restarts);
}
BENCHMARK(BM_Step_QuickBot5Ir_50Polygons_Planner)->MinTime(3.0);

void BM_Step_Lidar180_50Polygons(benchmark::State& state) {
  step_robot(state, lidar180_floor());
}
BENCHMARK(BM_Step_Lidar180_50Polygons);

void BM_Step_Lidar360_AwsWarehouse(benchmark::State& state) {
  static const std::optional<Scenario> s = make_aws_scenario(FLOORNAV_MAPS_DIR);
  if (!s) {
    state.SkipWithError("AWS warehouse map not found under " FLOORNAV_MAPS_DIR);
    return;
  }
  step_robot(state, *s);
}
BENCHMARK(BM_Step_Lidar360_AwsWarehouse);

/// Steps/s against the obstacle count: the 50-polygon floor's density at 10 .. 10,000 edges.
void BM_StepEdges_QuickBot5Ir(benchmark::State& state) {
  const Scenario s = make_factory_floor_scenario(floor_world(static_cast<int>(state.range(0))), 0);
  step_robot(state, s);
  state.counters["edges"] = static_cast<double>(s.world->edge_count());
}
BENCHMARK(BM_StepEdges_QuickBot5Ir)->RangeMultiplier(2)->Range(10, 10000);

void BM_StepEdges_Lidar180(benchmark::State& state) {
  const Scenario s =
      make_factory_floor_scenario(floor_world(static_cast<int>(state.range(0))), 180);
  step_robot(state, s);
  state.counters["edges"] = static_cast<double>(s.world->edge_count());
}
BENCHMARK(BM_StepEdges_Lidar180)->RangeMultiplier(2)->Range(10, 10000);

/// 100 lidar robots on one shared floor, stepped in lockstep (they do not sense each other: fleet
/// sensing is not implemented). One iteration advances every robot by one step.
void BM_FleetStep_100xLidar180_50Polygons(benchmark::State& state) {
  constexpr int kRobots = 100;
  static const std::vector<Scenario> scenarios = [] {
    std::vector<Scenario> v;
    for (int i = 0; i < kRobots; ++i)
      v.push_back(make_factory_floor_scenario(floor_world(0), 180, i));
    return v;
  }();
  std::vector<std::optional<Simulation>> sims(kRobots);
  for (int i = 0; i < kRobots; ++i) {
    const Scenario& sc = scenarios[static_cast<std::size_t>(i)];
    sims[static_cast<std::size_t>(i)].emplace(*sc.world, sc.robot(), sc.sim, sc.name);
  }
  std::vector<int> ended;
  ended.reserve(kRobots);
  for (auto _ : state) {
    for (int i = 0; i < kRobots; ++i)
      if (!sims[static_cast<std::size_t>(i)]->step()) ended.push_back(i);
    if (!ended.empty()) {
      state.PauseTiming();
      for (int i : ended) {
        const Scenario& sc = scenarios[static_cast<std::size_t>(i)];
        sims[static_cast<std::size_t>(i)].emplace(*sc.world, sc.robot(), sc.sim, sc.name);
      }
      ended.clear();
      state.ResumeTiming();
    }
  }
  state.SetItemsProcessed(state.iterations() * kRobots);
  state.counters["rays"] = benchmark::Counter(
      rays_per_step(scenarios[0]) * kRobots * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FleetStep_100xLidar180_50Polygons);

/// Whole runs of a chapter scenario, as `floornav run` simulates it (trajectory recorded).
void run_scenario(benchmark::State& state, const char* file) {
  const Scenario s = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + file);
  std::int64_t steps = 0;
  for (auto _ : state) {
    const RunResult r = simulate(s);
    steps += r.steps;
  }
  state.SetItemsProcessed(steps);
  state.counters["steps_per_run"] =
      static_cast<double>(steps) / static_cast<double>(state.iterations());
}
BENCHMARK_CAPTURE(run_scenario, factory_delivery, "factory_delivery.yaml")
    ->Name("BM_Run/factory_delivery")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_scenario, rectangle, "rectangle.yaml")
    ->Name("BM_Run/rectangle")
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace floornav
