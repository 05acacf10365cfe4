// Ray casting and clearance on a real occupancy map: the AWS RoboMaker small warehouse (ROS
// map_server, 286 x 423 cells of 0.05 m; data/maps). items_per_second is rays/s (queries/s). And
// a 180-beam lidar's fan at 3.5 m and 8 m on a cave-like map shaped like Stage's (16 x 16 m,
// 0.032 m cells; cave_map.hpp).
//
//   floornav_bench --benchmark_filter='BM_Grid|BM_Cave'

#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bench_cases.hpp"
#include "cave_map.hpp"
#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/io/ros_map.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace {

constexpr std::size_t kSamples = 1024;

struct WarehouseMap {
  std::shared_ptr<const OccupancyGrid> grid;  ///< null when the map is missing
  std::unique_ptr<World> world;  ///< the grid as a World (what the simulation casts into)
  std::vector<Vec2> origins;     ///< free points, >= 0.2 m from anything
  std::vector<Vec2> dirs;
  std::string path;
};

const WarehouseMap& warehouse() {
  static const WarehouseMap map = [] {
    WarehouseMap m;
    m.path = aws_warehouse_map(FLOORNAV_MAPS_DIR).string();
    std::error_code ec;
    if (!std::filesystem::exists(m.path, ec)) return m;
    m.grid = std::make_shared<const OccupancyGrid>(load_ros_map(m.path));
    WorldDesc desc;
    desc.grid = m.grid;
    m.world = std::make_unique<World>(std::move(desc));
    Vec2 lo, hi;
    m.grid->world_extent(&lo, &hi);
    Rng rng(11);
    while (m.origins.size() < kSamples) {
      const Vec2 p = lo + Vec2((hi - lo).x() * rng.uniform(), (hi - lo).y() * rng.uniform());
      if (m.grid->clearance(p) < 0.2) continue;
      const double a = 2.0 * kPi * rng.uniform();
      m.origins.push_back(p);
      m.dirs.emplace_back(std::cos(a), std::sin(a));
    }
    return m;
  }();
  return map;
}

bool skip_if_missing(benchmark::State& state, const WarehouseMap& m) {
  if (m.grid) return false;
  state.SkipWithError(("skipped: map not found at " + m.path).c_str());
  return true;
}

/// Argument: the ray's maximum range in centimetres (350: TurtleBot3 LDS-01, 3000: Jackal).
void BM_GridCastRay(benchmark::State& state) {
  const WarehouseMap& m = warehouse();
  if (skip_if_missing(state, m)) return;
  const double range = static_cast<double>(state.range(0)) / 100.0;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.grid->cast_ray(m.origins[i], m.dirs[i], range));
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GridCastRay)->Arg(350)->Arg(3000);

/// The same rays walked cell by cell (OccupancyGrid::cast_ray_cell_by_cell, the reference that
/// cast_ray's free-space jumps match bit for bit).
void BM_GridCastRayCellByCell(benchmark::State& state) {
  const WarehouseMap& m = warehouse();
  if (skip_if_missing(state, m)) return;
  const double range = static_cast<double>(state.range(0)) / 100.0;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.grid->cast_ray_cell_by_cell(m.origins[i], m.dirs[i], range));
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GridCastRayCellByCell)->Arg(350)->Arg(3000);

/// The same rays through World::cast_ray (the path the simulation takes).
void BM_GridWorldCastRay(benchmark::State& state) {
  const WarehouseMap& m = warehouse();
  if (skip_if_missing(state, m)) return;
  const double range = static_cast<double>(state.range(0)) / 100.0;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.world->cast_ray(m.origins[i], m.dirs[i], range));
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GridWorldCastRay)->Arg(350)->Arg(3000);

/// A 360-beam fan (1 degree apart) from each sample origin: OccupancyGrid::cast_fan against the
/// same beams one cast_ray at a time. Items are rays. The directions are computed beforehand.
void grid_fan(benchmark::State& state, bool fan) {
  const WarehouseMap& m = warehouse();
  if (skip_if_missing(state, m)) return;
  const double range = static_cast<double>(state.range(0)) / 100.0;
  constexpr int kBeams = 360;
  constexpr std::size_t kSets = 8;  // fans turned by 0.37 rad from one set to the next
  std::vector<std::vector<Vec2>> dir_sets(kSets, std::vector<Vec2>(kBeams));
  std::vector<std::vector<double>> angle_sets(kSets, std::vector<double>(kBeams));
  for (std::size_t j = 0; j < kSets; ++j) {
    for (int k = 0; k < kBeams; ++k) {
      angle_sets[j][k] = wrap_angle(0.37 * static_cast<double>(j) + 2.0 * kPi * k / kBeams);
      dir_sets[j][k] = Vec2(std::cos(angle_sets[j][k]), std::sin(angle_sets[j][k]));
    }
  }
  std::vector<double> out(kBeams);
  FanScratch scratch;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::vector<Vec2>& dirs = dir_sets[i % kSets];
    const std::vector<double>& angles = angle_sets[i % kSets];
    if (fan) {
      m.grid->cast_fan(m.origins[i], dirs, angles, range, out, scratch);
    } else {
      for (int k = 0; k < kBeams; ++k) out[k] = m.grid->cast_ray(m.origins[i], dirs[k], range);
    }
    benchmark::DoNotOptimize(out.data());
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations() * kBeams);
}
void BM_GridCastFan360(benchmark::State& state) {
  grid_fan(state, true);
}
void BM_GridCastFan360PerRay(benchmark::State& state) {
  grid_fan(state, false);
}
BENCHMARK(BM_GridCastFan360)->Arg(350)->Arg(3000);
BENCHMARK(BM_GridCastFan360PerRay)->Arg(350)->Arg(3000);

void BM_GridClearance(benchmark::State& state) {
  const WarehouseMap& m = warehouse();
  if (skip_if_missing(state, m)) return;
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(m.grid->clearance(m.origins[i]));
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_GridClearance);

/// The cave map, origins in its open hall (>= 0.2 m from any wall) and 8 fans of 180 beams
/// (2 degrees apart; turned by 0.37 rad from one to the next), as a lidar's.
struct CaveFans {
  bench::CaveMap map;
  std::vector<Vec2> origins;
  std::vector<std::vector<Vec2>> dirs;
  std::vector<std::vector<double>> angles;
  /// The same, 180 beams over 180 degrees (1.006 degrees apart), as the peer benchmark's laser.
  std::vector<std::vector<Vec2>> half_dirs;
  std::vector<std::vector<double>> half_angles;
};

constexpr int kCaveBeams = 180;

const CaveFans& cave_fans() {
  static const CaveFans fans = [] {
    CaveFans f;
    f.map = bench::make_cave_map();
    Rng rng(5);
    while (f.origins.size() < kSamples) {
      const Vec2 p(16.0 * rng.uniform(), 16.0 * rng.uniform());
      if (f.map.in_hall(p, 0.2) && f.map.grid->clearance(p) >= 0.2) f.origins.push_back(p);
    }
    for (int j = 0; j < 8; ++j) {
      f.dirs.emplace_back(kCaveBeams);
      f.angles.emplace_back(kCaveBeams);
      for (int k = 0; k < kCaveBeams; ++k) {
        const double a = wrap_angle(0.37 * j + 2.0 * kPi * k / kCaveBeams);
        f.angles[j][k] = a;
        f.dirs[j][k] = Vec2(std::cos(a), std::sin(a));
      }
      f.half_dirs.emplace_back(kCaveBeams);
      f.half_angles.emplace_back(kCaveBeams);
      for (int k = 0; k < kCaveBeams; ++k) {
        const double a = wrap_angle(0.37 * j - 0.5 * kPi + kPi * k / (kCaveBeams - 1));
        f.half_angles[j][k] = a;
        f.half_dirs[j][k] = Vec2(std::cos(a), std::sin(a));
      }
    }
    return f;
  }();
  return fans;
}

/// Argument: the beams' range in centimetres (350: TurtleBot3 LDS-01; 800: Stage's sicklaser).
/// How: 0 the fan (OccupancyGrid::cast_fan), 1 cast_ray per beam, 2 cast_ray_cell_by_cell per
/// beam (the oracle). Items are rays. `half`: the 180-degree laser instead of the full turn.
void cave_fan(benchmark::State& state, int how, bool half = false) {
  const CaveFans& f = cave_fans();
  const OccupancyGrid& grid = *f.map.grid;
  const double range = static_cast<double>(state.range(0)) / 100.0;
  std::vector<double> out(kCaveBeams);
  FanScratch scratch;
  std::size_t i = 0;
  for (auto _ : state) {
    const std::vector<Vec2>& dirs = half ? f.half_dirs[i % 8] : f.dirs[i % 8];
    const Vec2& o = f.origins[i];
    if (how == 0) {
      grid.cast_fan(o, dirs, half ? f.half_angles[i % 8] : f.angles[i % 8], range, out, scratch);
    } else if (how == 1) {
      for (int k = 0; k < kCaveBeams; ++k) out[k] = grid.cast_ray(o, dirs[k], range);
    } else {
      for (int k = 0; k < kCaveBeams; ++k) out[k] = grid.cast_ray_cell_by_cell(o, dirs[k], range);
    }
    benchmark::DoNotOptimize(out.data());
    i = (i + 1) & (kSamples - 1);
  }
  state.SetItemsProcessed(state.iterations() * kCaveBeams);
}
void BM_CaveGridCastFan180(benchmark::State& state) {
  cave_fan(state, 0);
}
void BM_CaveGridCastRay180(benchmark::State& state) {
  cave_fan(state, 1);
}
void BM_CaveGridCellByCell180(benchmark::State& state) {
  cave_fan(state, 2);
}
/// The peer benchmark's laser: 180 beams over 180 degrees.
void BM_CaveGridCastFanHalfTurn180(benchmark::State& state) {
  cave_fan(state, 0, true);
}
void BM_CaveGridCastRayHalfTurn180(benchmark::State& state) {
  cave_fan(state, 1, true);
}
BENCHMARK(BM_CaveGridCastFan180)->Arg(350)->Arg(800);
BENCHMARK(BM_CaveGridCastFanHalfTurn180)->Arg(800);
BENCHMARK(BM_CaveGridCastRayHalfTurn180)->Arg(800);
BENCHMARK(BM_CaveGridCastRay180)->Arg(350)->Arg(800);
BENCHMARK(BM_CaveGridCellByCell180)->Arg(350)->Arg(800);

}  // namespace
}  // namespace floornav
