#include "floornav/runner/run_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "floornav/io/atomic_file.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/io/trajectory_csv.hpp"
#include "floornav/render/trajectory_html.hpp"
#include "floornav/render/trajectory_svg.hpp"
#include "floornav/scenario/simulate.hpp"

namespace floornav {

void write_run_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                       const RunResult& result, const OutputSelection& which) {
  ensure_directory(dir);
  if (which.summary)
    write_file_atomically(dir / "summary.json", summary_to_json(result).dump(2) + "\n");
  if (which.csv) write_file_atomically(dir / "trajectory.csv", trajectory_to_csv(result));
  if (which.svg)
    write_file_atomically(dir / "trajectory.svg", render_trajectory_svg(scenario, result));
  if (which.html && !result.trajectory.empty())
    write_file_atomically(dir / "trajectory.html", render_trajectory_html(scenario, result));
}

void prepare_outputs(Scenario& scenario, const OutputSelection& which) {
  if (which.html && scenario.sim.record_trajectory && scenario.sim.record_ranges_every == 0)
    scenario.sim.record_ranges_every = replay_ranges_interval(scenario);
}

std::string describe_run(const RunResult& r) {
  std::string out = fmt::format(
      "{}: {} in {:.1f} s, path {:.2f} m, min clearance {:.3f} m, {} "
      "switch{}",
      r.scenario, to_string(r.status), r.sim_time, r.path_length, r.min_clearance, r.mode_switches,
      r.mode_switches == 1 ? "" : "es");
  if (r.goal_count > 1) out += fmt::format(", {}/{} goals", r.goals_reached, r.goal_count);
  if (r.chatter_episodes > 0)
    out += fmt::format(", chatter (Zeno) from t = {:.2f} s", r.first_chatter_time);
  return out;
}

RunResult run_timed(const Scenario& scenario) {
  const auto t0 = std::chrono::steady_clock::now();
  RunResult r = simulate(scenario);
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void write_fleet_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                         const FleetResult& result, const OutputSelection& which) {
  ensure_directory(dir);
  if (which.summary)
    write_file_atomically(dir / "summary.json", fleet_summary_to_json(result).dump(2) + "\n");
  if (which.csv)
    write_file_atomically(dir / "trajectory.csv",
                          [&](const std::function<void(std::string_view)>& sink) {
                            trajectory_csv_pieces(result, sink);
                          });
  if (which.svg) write_file_atomically(dir / "trajectory.svg", render_fleet_svg(scenario, result));
  const bool recorded = std::any_of(result.robots.begin(), result.robots.end(),
                                    [](const RunResult& r) { return !r.trajectory.empty(); });
  if (which.html && recorded)
    write_file_atomically(dir / "trajectory.html", render_fleet_html(scenario, result));
}

std::string describe_fleet(const FleetResult& f) {
  std::string out = fmt::format(
      "{}: {} robots, {} reached, {} collided, {}/{} deliveries in {:.1f} s, min clearance "
      "{:.3f} m",
      f.scenario, f.robots.size(), f.reached, f.collided, f.deliveries, f.delivery_count,
      f.sim_time, f.min_clearance);
  return out;
}

FleetResult run_fleet_timed(const Scenario& scenario, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  FleetResult r = simulate_fleet(scenario, threads);
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace floornav
