// The path-efficiency optimum of `floornav batch --floors` (scenario_optimum): the generated
// floors 1-40 of the batch (a walled 20 x 20 m hall with 50 star-shaped obstacles, a QuickBot
// touring four goals), one floor per iteration in turn. items_per_second is floors per second.
//
//   floornav_bench --benchmark_filter='BM_FloorOptimum'
//
// BM_FloorOptimum: raster and search, as the batch does for a floor it has not seen;
// BM_FloorOptimumRaster: the raster alone (build_optimum_raster);
// BM_FloorOptimumSearch: the four legs' search (jump point search) and their string pulling on a
// raster built beforehand;
// BM_FloorOptimumAstar: the four legs by octile A* alone (GridSearch, the planners' search), with
// the cells it expands per floor.

#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "bench_cases.hpp"
#include "floornav/planning/octile_astar.hpp"
#include "floornav/runner/scenario_optimum.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

struct FloorCase {
  std::shared_ptr<const World> world;
  Scenario scenario;
  OptimumRaster raster;
};

/// The batch's floors 1-40: the world and tour `make_floor_cases` (app/batch_sources.cpp) gives.
const std::vector<FloorCase>& floors() {
  static const std::vector<FloorCase> cases = [] {
    std::vector<FloorCase> out;
    for (int seed = 1; seed <= 40; ++seed) {
      FactoryFloorParams p;
      p.seed = static_cast<std::uint64_t>(seed);
      FloorCase c;
      c.world = std::make_shared<const World>(make_factory_floor(p));
      c.scenario = make_factory_floor_scenario(c.world, 0, seed);
      build_optimum_raster(*c.world, c.scenario.robot().robot.body_radius, {}, c.raster);
      out.push_back(std::move(c));
    }
    return out;
  }();
  return cases;
}

/// `body` on the floors in turn, one floor per iteration (items_per_second: floors per second).
template <class Body>
void over_floors(benchmark::State& state, Body&& body) {
  const auto& cases = floors();
  std::size_t i = 0;
  for (auto _ : state) body(cases[i++ % cases.size()]);
  state.SetItemsProcessed(state.iterations());
}

void BM_FloorOptimum(benchmark::State& state) {
  over_floors(state, [](const FloorCase& c) {
    const RobotTask& t = c.scenario.robot();
    const Optimum o = scenario_optimum(*c.world, t.robot.body_radius, t.start.position, t.goals);
    benchmark::DoNotOptimize(o.length);
  });
}

void BM_FloorOptimumRaster(benchmark::State& state) {
  OptimumRaster raster;
  over_floors(state, [&](const FloorCase& c) {
    build_optimum_raster(*c.world, c.scenario.robot().robot.body_radius, {}, raster);
    benchmark::DoNotOptimize(raster.raster.free.data());
  });
}

void BM_FloorOptimumSearch(benchmark::State& state) {
  over_floors(state, [](const FloorCase& c) {
    const RobotTask& t = c.scenario.robot();
    const Optimum o = scenario_optimum(c.raster, t.start.position, t.goals);
    benchmark::DoNotOptimize(o.length);
  });
}

/// The octile A* of the four legs alone (GridSearch, cells snapped as scenario_optimum does);
/// `expanded` is the cells expanded per floor.
void BM_FloorOptimumAstar(benchmark::State& state) {
  GridSearch search;
  GridPath path;
  double expanded = 0.0;
  over_floors(state, [&](const FloorCase& c) {
    const RobotTask& t = c.scenario.robot();
    const RasterFrame frame{c.raster.origin, c.raster.cell, c.raster.raster.width,
                            c.raster.raster.height};
    auto from = snap_to_free(c.raster.raster, frame.to_cells(t.start.position), 3.0);
    for (const Vec2& g : t.goals) {
      const auto to = snap_to_free(c.raster.raster, frame.to_cells(g), 3.0);
      if (from && to) {
        search.search(c.raster.raster, *from, *to, path);
        expanded += static_cast<double>(search.expanded());
      }
      from = to;
    }
    benchmark::DoNotOptimize(path.length);
  });
  state.counters["expanded"] = expanded / static_cast<double>(state.iterations());
  state.counters["cells"] = static_cast<double>(floors()[0].raster.raster.free.size());
}

BENCHMARK(BM_FloorOptimum)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FloorOptimumRaster)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FloorOptimumSearch)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FloorOptimumAstar)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace floornav
