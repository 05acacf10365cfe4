// World queries against the number of obstacle edges (10 .. 10,000): the uniform-grid index
// (World::cast_ray, World::clearance) and the brute-force oracles, in the same run so that their
// ratio is measured on one machine at one moment. items_per_second is rays/s (queries/s).
//
//   floornav_bench --benchmark_filter='BM_World' --benchmark_out=world.json
//   python3 bench/plot_scaling.py world.json docs/images/scaling_edges.svg

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <memory>
#include <vector>

#include "bench_cases.hpp"
#include "floornav/common/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/world.hpp"

namespace floornav {
namespace {

constexpr std::size_t kSamples = 1024;  // power of two: the index wraps with a mask
constexpr double kMaxRange = 3.5;       // m, the lidars' range in the simulation benchmarks

/// A floor with a given number of edges and fixed query samples in its free space.
struct EdgeFloor {
  std::unique_ptr<World> world;
  std::vector<Vec2> origins;  ///< free points
  std::vector<Vec2> dirs;     ///< unit directions
};

const EdgeFloor& edge_floor(int edges) {
  static std::map<int, EdgeFloor> cache;  // built outside the timed loops
  auto it = cache.find(edges);
  if (it != cache.end()) return it->second;
  EdgeFloor f;
  f.world = std::make_unique<World>(make_bench_floor(bench_floor_with_edges(edges)));
  const Vec2 lo = f.world->extent().min, size = f.world->extent().size();
  Rng rng(7);
  while (f.origins.size() < kSamples) {
    const Vec2 p = lo + Vec2(size.x() * rng.uniform(), size.y() * rng.uniform());
    if (f.world->is_inside_obstacle(p)) continue;
    const double a = 2.0 * kPi * rng.uniform();
    f.origins.push_back(p);
    f.dirs.emplace_back(std::cos(a), std::sin(a));
  }
  return cache.emplace(edges, std::move(f)).first->second;
}

void set_counters(benchmark::State& state, const World& world) {
  state.SetItemsProcessed(state.iterations());
  state.counters["edges"] = static_cast<double>(world.edge_count());
}

void BM_WorldCastRay_Indexed(benchmark::State& state) {
  const EdgeFloor& f = edge_floor(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.world->cast_ray(f.origins[i], f.dirs[i], kMaxRange));
    i = (i + 1) & (kSamples - 1);
  }
  set_counters(state, *f.world);
}

void BM_WorldCastRay_BruteForce(benchmark::State& state) {
  const EdgeFloor& f = edge_floor(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.world->cast_ray_brute_force(f.origins[i], f.dirs[i], kMaxRange));
    i = (i + 1) & (kSamples - 1);
  }
  set_counters(state, *f.world);
}

void BM_WorldClearance_Indexed(benchmark::State& state) {
  const EdgeFloor& f = edge_floor(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.world->clearance(f.origins[i]));
    i = (i + 1) & (kSamples - 1);
  }
  set_counters(state, *f.world);
}

void BM_WorldClearance_BruteForce(benchmark::State& state) {
  const EdgeFloor& f = edge_floor(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(f.world->clearance_brute_force(f.origins[i]));
    i = (i + 1) & (kSamples - 1);
  }
  set_counters(state, *f.world);
}

// 10, 16, 32, ..., 8192, 10000 polygon edges (plus the four walls).
BENCHMARK(BM_WorldCastRay_Indexed)->RangeMultiplier(2)->Range(10, 10000);
BENCHMARK(BM_WorldCastRay_BruteForce)->RangeMultiplier(2)->Range(10, 10000);
BENCHMARK(BM_WorldClearance_Indexed)->RangeMultiplier(2)->Range(10, 10000);
BENCHMARK(BM_WorldClearance_BruteForce)->RangeMultiplier(2)->Range(10, 10000);

}  // namespace
}  // namespace floornav
