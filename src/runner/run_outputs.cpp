#include "floornav/runner/run_outputs.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>

#include "floornav/core/input_error.hpp"
#include "floornav/io/atomic_file.hpp"
#include "floornav/io/crowd_csv.hpp"
#include "floornav/io/run_mcap.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/io/trajectory_csv.hpp"
#include "floornav/render/trajectory_html.hpp"
#include "floornav/render/trajectory_svg.hpp"
#include "floornav/scenario/ranges_interval.hpp"
#include "floornav/scenario/simulate.hpp"

namespace floornav {

namespace {
/// A clearance for the one-line report: "none" when nothing was ever near enough to measure.
std::string clearance_text(double c) {
  return std::isfinite(c) ? fmt::format("{:.3f} m", c) : std::string("none");
}

/// run.mcap made on another thread while the other files are written (its zstd and CRC are most
/// of its cost), straight into its file piece by piece as the writer hands them over: no copy of
/// the bag is held (copying megabytes into fresh memory cost a fifth of the bag's time in page
/// faults). The future is declared after the folder: it is waited for before the folder goes.
std::future<void> bag_in_background(OutputFolder& out, std::function<void(const McapSink&)> write) {
  return std::async(std::launch::async, [&out, write = std::move(write)] {
    out.write("run.mcap", [&](const std::function<void(std::string_view)>& sink) { write(sink); });
  });
}
}  // namespace

const std::vector<std::string>& run_output_files() {
  static const std::vector<std::string> names = {
      "summary.json",    "trajectory.csv", "transitions.csv", "trajectory.svg",
      "trajectory.html", "crowd.csv",      "run.mcap"};
  return names;
}

void check_recording_limits(const Scenario& s, const std::string& file) {
  if (!s.sim.record_trajectory) return;
  const double steps = std::ceil(s.sim.t_max / s.sim.dt) + 1;
  const double movers = static_cast<double>(s.crowd.people.size() + s.crowd.forklifts.size());
  const double rows = (static_cast<double>(s.robots.size()) + movers) * steps;
  if (rows > kMaxRecordedRows)
    throw InputError(
        file, "sim.record_trajectory",
        fmt::format("recording {} robot(s){} for {:.6g} steps is {:.3g} rows, more than the "
                    "{:.0e} a run may record: set sim.record_trajectory: false (the summary is "
                    "still written) or a shorter sim.t_max",
                    s.robots.size(),
                    movers > 0 ? fmt::format(" and {} people and forklifts", movers) : "",
                    steps - 1, rows, kMaxRecordedRows));
  std::size_t sensors = 0;
  for (const RobotTask& t : s.robots) sensors = std::max(sensors, t.robot.sensors.size());
  const RecordOptions& o = s.sim.record;
  const double columns = 9.0 + 4.0 * o.command + 2.0 * o.heading + o.clearance + 3.0 * o.goal +
                         (o.ranges ? static_cast<double>(sensors) : 0.0);
  if (rows * columns > kMaxRecordedValues)
    throw InputError("", "--record",
                     fmt::format("{:.3g} rows of {} columns is more than the {:.0e} numbers a run "
                                 "may record: record fewer columns or a shorter run",
                                 rows, columns, kMaxRecordedValues));
}

void write_run_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                       const RunResult& result, const OutputSelection& which) {
  write_run_outputs(dir, scenario, result, RunContext{}, which);
}

void write_run_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                       const RunResult& result, const RunContext& context,
                       const OutputSelection& which) {
  // Every file of the run appears together, or none does (a full disk, a signal).
  OutputFolder out(dir, run_output_files());
  std::future<void> bag;
  if (which.mcap && !result.trajectory.empty())
    bag = bag_in_background(out,
                            [&](const McapSink& sink) { write_run_mcap(scenario, result, sink); });
  if (which.summary)
    out.write("summary.json", run_summary(scenario, result, context).dump(2) + "\n");
  if (which.csv)
    out.write("trajectory.csv", [&](const std::function<void(std::string_view)>& sink) {
      trajectory_csv_pieces(result, sink);
    });
  if (which.transitions)
    out.write("transitions.csv", transitions_to_csv(result, scenario.robot().name));
  if (which.svg) out.write("trajectory.svg", render_trajectory_svg(scenario, result));
  if (which.html && !result.trajectory.empty())
    out.write("trajectory.html", render_trajectory_html(scenario, result));
  if (bag.valid()) bag.get();  // its failure, if any, is thrown here
  out.commit();
}

void prepare_outputs(Scenario& scenario, const OutputSelection& which) {
  if (which.mcap) scenario.sim.record_trajectory = true;
  if (!scenario.sim.record_trajectory || scenario.sim.record_ranges_every != 0) return;
  const int replay = which.html ? replay_ranges_interval(scenario) : 0;
  const int bag = which.mcap ? mcap_ranges_interval(scenario) : 0;
  // Each its own interval: the steps of either are recorded, so the replay finds the frames a run
  // without the bag records (and draws the same), and the bag its own, without the frames at
  // their common divisor's steps that neither takes.
  scenario.sim.record_ranges_every = replay > 0 ? replay : bag;
  if (replay > 0 && bag > 0 && replay % bag != 0 && bag % replay != 0)
    scenario.sim.record_ranges_also_every = bag;
  else if (replay > 0 && bag > 0)
    scenario.sim.record_ranges_every = std::min(replay, bag);
}

std::string describe_run(const RunResult& r) {
  std::string out =
      fmt::format("{}: {} in {:.1f} s, path {:.2f} m, min clearance {}, {} switch{}", r.scenario,
                  to_string(r.status), r.sim_time, r.path_length, clearance_text(r.min_clearance),
                  r.mode_switches, r.mode_switches == 1 ? "" : "es");
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

std::optional<RunResult> run_timed(const Scenario& scenario, const std::atomic<bool>* stop,
                                   const std::atomic<bool>* also) {
  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim = make_simulation(scenario);
  // The stop flags are read once per step (relaxed loads): a case is abandoned mid-run, so that
  // an interrupt never waits for a long case to end.
  const auto stopped = [&] {
    return (stop != nullptr && stop->load(std::memory_order_relaxed)) ||
           (also != nullptr && also->load(std::memory_order_relaxed));
  };
  while (sim.step())
    if (stopped()) return std::nullopt;
  RunResult r = sim.take_result();
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

void write_fleet_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                         const FleetResult& result, const OutputSelection& which) {
  write_fleet_outputs(dir, scenario, result, RunContext{}, which);
}

void write_fleet_outputs(const std::filesystem::path& dir, const Scenario& scenario,
                         const FleetResult& result, const RunContext& context,
                         const OutputSelection& which) {
  OutputFolder out(dir, run_output_files());
  const bool recorded = std::any_of(result.robots.begin(), result.robots.end(),
                                    [](const RunResult& r) { return !r.trajectory.empty(); });
  std::future<void> bag;
  if (which.mcap && recorded)
    bag = bag_in_background(
        out, [&](const McapSink& sink) { write_fleet_mcap(scenario, result, sink); });
  if (which.summary)
    out.write("summary.json", fleet_run_summary(scenario, result, context).dump(2) + "\n");
  if (which.csv)
    out.write("trajectory.csv", [&](const std::function<void(std::string_view)>& sink) {
      trajectory_csv_pieces(result, sink);
    });
  if (which.transitions) out.write("transitions.csv", transitions_to_csv(result));
  if (which.svg) out.write("trajectory.svg", render_fleet_svg(scenario, result));
  if (which.html && recorded) out.write("trajectory.html", render_fleet_html(scenario, result));
  // People and forklifts: their tracks beside the robots'.
  if (which.csv && !result.crowd.empty()) out.write("crowd.csv", crowd_to_csv(result.crowd));
  if (bag.valid()) bag.get();  // its failure, if any, is thrown here
  out.commit();
}

std::string describe_fleet(const FleetResult& f) {
  std::string out = fmt::format(
      "{}: {} robots, {} reached, {} collided, {}/{} deliveries in {:.1f} s, min clearance {}",
      f.scenario, f.robots.size(), f.reached, f.collided, f.deliveries, f.delivery_count,
      f.sim_time, clearance_text(f.min_clearance));
  if (!f.crowd.empty())
    out += fmt::format(", {} people, {} forklifts: {} person and {} forklift contacts",
                       f.crowd.people.size(), f.crowd.forklifts.size(),
                       f.crowd.metrics.person_contacts, f.crowd.metrics.forklift_contacts);
  return out;
}

FleetResult run_fleet_timed(const Scenario& scenario, int threads) {
  const auto t0 = std::chrono::steady_clock::now();
  FleetResult r = simulate_fleet(scenario, threads);
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

std::optional<FleetResult> run_fleet_timed(const Scenario& scenario, int threads,
                                           const std::atomic<bool>* stop,
                                           const std::atomic<bool>* also) {
  const auto t0 = std::chrono::steady_clock::now();
  FleetSimulation sim = make_fleet_simulation(scenario);
  const auto stopped = [&] {
    return (stop != nullptr && stop->load(std::memory_order_relaxed)) ||
           (also != nullptr && also->load(std::memory_order_relaxed));
  };
  // A stop is looked at every 64 world steps (each step of a big fleet is long enough).
  while (sim.run_steps(64, threads) > 0 && !sim.finished())
    if (stopped()) return std::nullopt;
  if (!sim.finished() && stopped()) return std::nullopt;
  FleetResult r = sim.take_result();
  r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace floornav
