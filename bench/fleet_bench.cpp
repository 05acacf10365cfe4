// Fleets: robot-steps/s of FleetSimulation, where every robot senses the others' bodies and
// robot-robot contacts are checked each step, against the number of robots (1 to 100,000) and
// threads; RVO2's Circle as shipped; and one robot's steps/s against the number of lidar beams (5
// to 720).
//
//   floornav_bench --benchmark_filter='BM_Fleet|BM_StepBeams'
//
// items_per_second is robot-steps/s. A fleet iteration is a batch of world steps (about 10,000
// robot-steps); robots that finish park and no longer count.

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include <map>
#include <memory>
#include <optional>

#include "bench_cases.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/simulation.hpp"

namespace floornav {
namespace {

const Scenario& warehouse_fleet(int robots, int beams) {
  static std::map<std::pair<int, int>, Scenario> cache;
  auto it = cache.find({robots, beams});
  if (it == cache.end()) {
    auto world = std::make_shared<const World>(make_fleet_warehouse(robots));
    it = cache.emplace(std::pair{robots, beams}, make_fleet_scenario(world, robots, beams)).first;
  }
  return it->second;
}

void step_fleet(benchmark::State& state, const Scenario& s, int threads) {
  std::optional<FleetSimulation> sim(std::in_place, *s.world, s.robots, s.sim, s.name);
  // About 100,000 robot-steps per call of run_steps: it starts its threads once per call.
  const long long batch = std::max<long long>(1, 100000 / static_cast<long long>(s.robots.size()));
  sim->run_steps(1, threads);  // warm-up: threads, caches
  long long steps = 0;
  for (auto _ : state) {
    const long long before = sim->robot_steps();
    if (sim->run_steps(batch, threads) == 0) {
      state.PauseTiming();
      sim.emplace(*s.world, s.robots, s.sim, s.name);
      state.ResumeTiming();
      continue;
    }
    steps += sim->robot_steps() - before;
  }
  state.SetItemsProcessed(steps);
  state.counters["robots"] = static_cast<double>(s.robots.size());
  state.counters["threads"] = threads;
}

/// QuickBots (5 IR) in a warehouse with ~4 m^2 per robot; args: robots, threads.
void BM_Fleet_QuickBotWarehouse(benchmark::State& state) {
  const auto robots = static_cast<int>(state.range(0));
  step_fleet(state, warehouse_fleet(robots, 0), static_cast<int>(state.range(1)));
}
BENCHMARK(BM_Fleet_QuickBotWarehouse)
    ->ArgsProduct({{1, 10, 100, 1000, 10000, 100000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// RVO2's Circle as shipped (scenarios/circle/circle_N.yaml: QuickBots 0.3 m apart on a circle,
/// each bound for its antipode; the fleet defaults: the automaton, ORCA, the safety layer); args:
/// robots, threads. It times as much of a run as its time allows, from the start: the robots'
/// approach, cheaper than their crossing in the middle, and more of the run on two threads than
/// on one. The like-for-like with RVO2 times whole runs: `bench/peers/run.py --only circle`.
void BM_Fleet_Circle(benchmark::State& state) {
  static std::map<int, Scenario> cache;
  const auto robots = static_cast<int>(state.range(0));
  auto it = cache.find(robots);
  if (it == cache.end()) {
    Scenario s =
        load_scenario_file(fmt::format("{}/circle/circle_{}.yaml", FLOORNAV_SCENARIO_DIR, robots));
    s.sim.record_trajectory = false;
    it = cache.emplace(robots, std::move(s)).first;
  }
  step_fleet(state, it->second, static_cast<int>(state.range(1)));
}
BENCHMARK(BM_Fleet_Circle)
    ->ArgsProduct({{20, 100, 300, 1000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// 100 TurtleBot3 bases with 180-beam lidars sensing each other on the 50-polygon floor.
void BM_Fleet_100xLidar180_50Polygons(benchmark::State& state) {
  static const Scenario s =
      make_fleet_scenario(std::make_shared<const World>(make_factory_floor({})), 100, 180);
  step_fleet(state, s, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_Fleet_100xLidar180_50Polygons)->Arg(1)->Arg(2)->UseRealTime();

/// One robot, `beams`-beam 360-degree lidar, on the 50-polygon floor.
void BM_StepBeams_Lidar(benchmark::State& state) {
  static std::map<int, Scenario> cache;
  const auto beams = static_cast<int>(state.range(0));
  auto it = cache.find(beams);
  if (it == cache.end())
    it = cache
             .emplace(beams, make_factory_floor_scenario(
                                 std::make_shared<const World>(make_factory_floor({})), beams))
             .first;
  std::optional<Simulation> sim(std::in_place, *it->second.world, it->second.robot(),
                                it->second.sim, it->second.name);
  for (auto _ : state) {
    if (!sim->step()) {
      state.PauseTiming();
      sim.emplace(*it->second.world, it->second.robot(), it->second.sim, it->second.name);
      state.ResumeTiming();
    }
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["rays"] = benchmark::Counter(static_cast<double>(beams) * state.iterations(),
                                              benchmark::Counter::kIsRate);
}
BENCHMARK(BM_StepBeams_Lidar)
    ->Arg(5)
    ->Arg(10)
    ->Arg(20)
    ->Arg(45)
    ->Arg(90)
    ->Arg(180)
    ->Arg(360)
    ->Arg(720);

}  // namespace
}  // namespace floornav
