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
#include "cave_map.hpp"
#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/world/world.hpp"

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
  f.world = std::make_unique<World>(make_factory_floor(factory_floor_with_edges(edges)));
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

/// A 180-beam, 360-degree lidar's rays from each sample origin: World::cast_fan against one
/// World::cast_ray per beam, on the floor with `edges` edges. items_per_second is rays/s.
struct Fan {
  std::vector<Vec2> dirs;
  std::vector<double> angles;
  std::vector<double> out;
};

Fan lidar_fan(int beams, double first) {
  Fan fan;
  for (int k = 0; k < beams; ++k) {
    const double a = wrap_angle(first + 2.0 * kPi * k / beams);
    fan.angles.push_back(a);
    fan.dirs.emplace_back(std::cos(a), std::sin(a));
  }
  fan.out.resize(static_cast<std::size_t>(beams));
  return fan;
}

void BM_Fan_CastFan(benchmark::State& state) {
  const EdgeFloor& f = edge_floor(static_cast<int>(state.range(0)));
  Fan fan = lidar_fan(180, 0.1);
  FanScratch scratch;
  std::size_t i = 0;
  for (auto _ : state) {
    f.world->cast_fan(f.origins[i], fan.dirs, fan.angles, kMaxRange, fan.out, scratch);
    benchmark::DoNotOptimize(fan.out.data());
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations() * 180);
  state.counters["edges"] = static_cast<double>(f.world->edge_count());
}

void BM_Fan_PerRay(benchmark::State& state) {
  const EdgeFloor& f = edge_floor(static_cast<int>(state.range(0)));
  Fan fan = lidar_fan(180, 0.1);
  std::size_t i = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < fan.dirs.size(); ++k)
      fan.out[k] = f.world->cast_ray(f.origins[i], fan.dirs[k], kMaxRange);
    benchmark::DoNotOptimize(fan.out.data());
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations() * 180);
  state.counters["edges"] = static_cast<double>(f.world->edge_count());
}

// The 50-polygon floor's density at about 280 and 10,000 edges.
BENCHMARK(BM_Fan_CastFan)->Arg(280)->Arg(10000);
BENCHMARK(BM_Fan_PerRay)->Arg(280)->Arg(10000);

/// A 180-beam lidar on the cave-like grid map (cave_map.hpp: 16 x 16 m, 0.032 m cells) through
/// World::cast_fan_from_free, the call a simulated robot's sensing makes, at the argument's range
/// in centimetres (350: TurtleBot3 LDS-01; 800: Stage's sicklaser). Items are rays.
void BM_CaveWorldCastFan180(benchmark::State& state) {
  static const struct Cave {
    bench::CaveMap map = bench::make_cave_map();
    std::unique_ptr<World> world;
    std::vector<Vec2> origins;
  } cave = [] {
    Cave c;
    WorldDesc desc;
    desc.grid = c.map.grid;
    c.world = std::make_unique<World>(std::move(desc));
    Rng rng(5);
    while (c.origins.size() < kSamples) {
      const Vec2 p(16.0 * rng.uniform(), 16.0 * rng.uniform());
      if (c.map.in_hall(p, 0.2) && c.map.grid->clearance(p) >= 0.2) c.origins.push_back(p);
    }
    return c;
  }();
  const double range = static_cast<double>(state.range(0)) / 100.0;
  std::vector<Fan> fans;
  for (int j = 0; j < 8; ++j) fans.push_back(lidar_fan(180, 0.37 * j));
  FanScratch scratch;
  std::size_t i = 0;
  for (auto _ : state) {
    Fan& fan = fans[i % 8];
    cave.world->cast_fan_from_free(cave.origins[i], fan.dirs, fan.angles, range, fan.out, scratch);
    benchmark::DoNotOptimize(fan.out.data());
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations() * 180);
}
BENCHMARK(BM_CaveWorldCastFan180)->Arg(350)->Arg(800);

}  // namespace
}  // namespace floornav
