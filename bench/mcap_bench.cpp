// What --mcap costs: a run as `floornav run` does it (simulate, then summary.json, trajectory.csv,
// transitions.csv, trajectory.svg and trajectory.html), without and with run.mcap (the run then
// also records what the bag needs). The budget: the bag adds at most 15 % to a run's wall
// time; the ratio is BM_RunOutputs/<scenario>/mcap over BM_RunOutputs/<scenario>/plain.
//
//   floornav_bench --benchmark_filter=BM_RunOutputs --benchmark_repetitions=5
//
// Scenarios: the factory demo (a QuickBot's IR ring), a TurtleBot's 360-beam lidar on Nav2's depot
// map (data/maps), and a fleet with people and forklifts. The files go to a temporary folder.

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <string_view>

#include "floornav/io/run_mcap.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/scenario/simulate.hpp"

namespace floornav {
namespace {

void run_outputs(benchmark::State& state, const std::string& file, bool mcap) {
  const Scenario s = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + file);
  OutputSelection which;
  which.mcap = mcap;
  Scenario recorded = s;
  prepare_outputs(recorded, which);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("floornav_mcap_bench_" + std::to_string(::getpid()));
  for (auto _ : state) {
    if (s.is_fleet())
      write_fleet_outputs(dir, s, simulate_fleet(recorded, 1), which);
    else
      write_run_outputs(dir, s, simulate(recorded), which);
  }
  std::error_code ignored;
  std::filesystem::remove_all(dir, ignored);
}

/// The bag alone, from a run recorded once, into a sink that keeps nothing: bytes/s of bag.
void write_bag(benchmark::State& state, const std::string& file) {
  Scenario s = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + file);
  prepare_outputs(s, OutputSelection{.html = false, .mcap = true});
  const RunResult r = simulate(s);
  std::size_t bytes = 0;
  for (auto _ : state) write_run_mcap(s, r, [&](std::string_view piece) { bytes += piece.size(); });
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}
/// The same for a fleet: six QuickBots' odometry at 100 Hz, 55 MB of records (the most of the four
/// scenes of docs/PERFORMANCE.md).
void write_fleet_bag(benchmark::State& state, const std::string& file) {
  Scenario s = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + file);
  prepare_outputs(s, OutputSelection{.html = false, .mcap = true});
  const FleetResult r = simulate_fleet(s, 1);
  std::size_t bytes = 0;
  for (auto _ : state)
    write_fleet_mcap(s, r, [&](std::string_view piece) { bytes += piece.size(); });
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
}
BENCHMARK_CAPTURE(write_fleet_bag, fleet, "fleet_aisles.yaml")
    ->Name("BM_WriteBag/fleet_aisles")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_bag, factory, "factory_delivery.yaml")
    ->Name("BM_WriteBag/factory_delivery")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(write_bag, depot, "ros/depot_1.yaml")
    ->Name("BM_WriteBag/depot_1")
    ->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(run_outputs, factory_plain, "factory_delivery.yaml", false)
    ->Name("BM_RunOutputs/factory_delivery/plain")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_outputs, factory_mcap, "factory_delivery.yaml", true)
    ->Name("BM_RunOutputs/factory_delivery/mcap")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_outputs, depot_plain, "ros/depot_1.yaml", false)
    ->Name("BM_RunOutputs/depot_1/plain")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_outputs, depot_mcap, "ros/depot_1.yaml", true)
    ->Name("BM_RunOutputs/depot_1/mcap")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_outputs, crowd_plain, "crowd/factory_people.yaml", false)
    ->Name("BM_RunOutputs/factory_people/plain")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(run_outputs, crowd_mcap, "crowd/factory_people.yaml", true)
    ->Name("BM_RunOutputs/factory_people/mcap")
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace floornav
