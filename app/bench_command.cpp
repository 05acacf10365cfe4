#include "bench_command.hpp"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "bench_cases.hpp"
#include "demo_scenario.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"

namespace fs = std::filesystem;

namespace floornav {

namespace {

using Clock = std::chrono::steady_clock;
using Seconds = std::chrono::duration<double>;

constexpr int kWarmUpSteps = 200;  // per robot, untimed: caches and branch predictors settle
constexpr int kChunk = 256;        // steps timed between two clock reads
constexpr int kFleetRobots = 100;  // the 100-lidar-robot case

/// What one case measured.
struct CaseResult {
  std::string name;
  std::string what;  ///< one line: the robot, the world
  int robots{1};
  std::uint64_t robot_steps{0};
  double seconds{0.0};        ///< timed
  double rays_per_step{0.0};  ///< per robot-step
  std::uint64_t runs{0};      ///< whole-run cases: runs completed
  std::uint64_t restarts{0};  ///< stepping cases: runs that ended and were restarted (untimed)
  std::string skipped;        ///< why the case did not run ("" if it ran)

  double steps_per_second() const { return seconds > 0.0 ? robot_steps / seconds : 0.0; }
  double ns_per_step() const { return robot_steps > 0 ? 1e9 * seconds / robot_steps : 0.0; }
};

double rays_per_step(const Scenario& s) {
  double n = 0.0;
  for (const RangeSensorSpec& r : s.robot().robot.sensors)
    n += (r.cone_rays > 1 && r.cone_angle > 0.0) ? r.cone_rays : 1;
  return n;
}

void require_running(const Simulation& sim, const std::string& name) {
  if (sim.finished()) throw std::runtime_error("bench case " + name + " ends before it starts");
}

/// One robot stepped for `budget` seconds of timed work. A run that ends is restarted outside
/// the timed chunks, so the timed loop holds nothing but Simulation::step().
void time_stepping(const Scenario& s, double budget, CaseResult& out) {
  std::optional<Simulation> sim(std::in_place, *s.world, s.robot(), s.sim, s.name);
  require_running(*sim, out.name);
  for (int i = 0; i < kWarmUpSteps; ++i)
    if (!sim->step()) sim.emplace(*s.world, s.robot(), s.sim, s.name);
  Clock::duration timed{};
  std::uint64_t steps = 0, restarts = 0;
  while (Seconds(timed).count() < budget) {
    bool ended = false;
    const Clock::time_point t0 = Clock::now();
    for (int i = 0; i < kChunk; ++i) {
      ++steps;
      if (!sim->step()) {
        ended = true;
        break;
      }
    }
    timed += Clock::now() - t0;
    if (ended) {
      sim.emplace(*s.world, s.robot(), s.sim, s.name);
      ++restarts;
    }
  }
  out.robot_steps = steps;
  out.seconds = Seconds(timed).count();
  out.restarts = restarts;
  out.rays_per_step = rays_per_step(s);
}

/// A fleet in one world (FleetSimulation: the robots sense each other, contacts are checked),
/// on `threads` threads; timed in batches of about 10,000 robot-steps.
void time_fleet(const Scenario& fleet, int threads, double budget, CaseResult& out) {
  std::optional<FleetSimulation> sim(std::in_place, *fleet.world, fleet.robots, fleet.sim,
                                     fleet.name);
  const long long batch =
      std::max<long long>(1, 10000 / static_cast<long long>(fleet.robots.size()));
  sim->run_steps(kWarmUpSteps / 10, threads);
  Clock::duration timed{};
  std::uint64_t steps = 0, restarts = 0;
  while (Seconds(timed).count() < budget) {
    const long long before = sim->robot_steps();
    const Clock::time_point t0 = Clock::now();
    const long long done = sim->run_steps(batch, threads);
    timed += Clock::now() - t0;
    steps += static_cast<std::uint64_t>(sim->robot_steps() - before);
    if (done == 0) {
      sim.emplace(*fleet.world, fleet.robots, fleet.sim, fleet.name);
      ++restarts;
    }
  }
  out.robots = static_cast<int>(fleet.robots.size());
  out.robot_steps = steps;
  out.seconds = Seconds(timed).count();
  out.restarts = restarts;
  out.rays_per_step = rays_per_step(fleet);
}

/// Whole runs of `s`, as `floornav run` simulates them (output files aside).
void time_runs(const Scenario& s, double budget, CaseResult& out) {
  simulate(s);  // warm-up
  Clock::duration timed{};
  std::uint64_t steps = 0, runs = 0;
  while (Seconds(timed).count() < budget) {
    const Clock::time_point t0 = Clock::now();
    const RunResult r = simulate(s);
    timed += Clock::now() - t0;
    steps += static_cast<std::uint64_t>(r.steps);
    ++runs;
  }
  out.robot_steps = steps;
  out.seconds = Seconds(timed).count();
  out.runs = runs;
  out.rays_per_step = rays_per_step(s);
}

/// The first of `candidates` that holds `probe`, or "" when none does.
fs::path find_dir(const std::vector<fs::path>& candidates, const fs::path& probe) {
  std::error_code ec;
  for (const fs::path& c : candidates)
    if (!c.empty() && fs::exists(c / probe, ec)) return c;
  return {};
}

fs::path source_tree() {
  return fs::path(__FILE__).parent_path().parent_path();  // app/.. (absolute under CMake)
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const std::size_t colon = line.find(':');
      if (colon != std::string::npos) {
        const std::size_t start = line.find_first_not_of(" \t", colon + 1);
        return start == std::string::npos ? "" : line.substr(start);
      }
    }
  }
  return "unknown";
}

std::string compiler() {
#if defined(__clang__)
  return std::string("clang ") + __clang_version__;
#elif defined(__GNUC__)
  return std::string("GCC ") + __VERSION__;
#else
  return "unknown";
#endif
}

std::string build_type() {
#if defined(__OPTIMIZE__) && defined(NDEBUG)
  return "optimised, NDEBUG (Release)";
#elif defined(__OPTIMIZE__)
  return "optimised, assertions on";
#else
  return "unoptimised (Debug)";
#endif
}

std::string utc_date() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

/// 1234567.8 -> "1,234,568".
std::string grouped(double v) {
  std::string digits = fmt::format("{:.0f}", v);
  std::string out;
  const std::size_t n = digits.size();
  for (std::size_t i = 0; i < n; ++i) {
    out += digits[i];
    const std::size_t left = n - 1 - i;
    if (left > 0 && left % 3 == 0 && digits[i] != '-') out += ',';
  }
  return out;
}

struct Case {
  std::string name;
  std::function<void(CaseResult&)> run;  ///< fills the result, or sets `skipped`
};

/// What the cases share: the time budget, where the shipped scenarios and maps are, and the
/// 50-polygon floor (built on first use, outside any timing).
class BenchInputs {
 public:
  explicit BenchInputs(const BenchOptions& options)
      : budget(options.seconds_per_case),
        scenario_dir(find_dir({options.scenario_dir, "scenarios", source_tree() / "scenarios"},
                              "rectangle.yaml")),
        maps_dir(
            find_dir({options.maps_dir, fs::path("data") / "maps", source_tree() / "data" / "maps"},
                     aws_warehouse_map("").relative_path())) {}

  std::shared_ptr<const World> floor50() {
    if (!floor_) floor_ = std::make_shared<const World>(make_factory_floor({}));
    return floor_;
  }

  /// A shipped scenario, or nullopt with `r` marked skipped when the folder was not found.
  std::optional<Scenario> scenario_file(const char* file, CaseResult& r) const {
    if (scenario_dir.empty()) {
      r.skipped =
          fmt::format("{} not found (run from the repository, or pass a scenario dir)", file);
      return std::nullopt;
    }
    return load_scenario_file(scenario_dir / file);
  }

  const double budget;  ///< timed seconds per case
  const fs::path scenario_dir;
  const fs::path maps_dir;

 private:
  std::shared_ptr<const World> floor_;
};

/// The standard cases, in the order of the table (each a name and how it is measured).
std::vector<Case> standard_cases(BenchInputs& in) {
  return {
      {"quickbot_5ir_50_polygons",
       [&in](CaseResult& r) {
         r.what = "QuickBot, 5 IR (0.3 m), 20 x 20 m floor of 50 random polygons";
         time_stepping(make_factory_floor_scenario(in.floor50(), 0), in.budget, r);
       }},
      {"quickbot_5ir_50_polygons_planner",
       [&in](CaseResult& r) {
         r.what =
             "the same QuickBot with the planner (A* on the known floor, a subgoal for the "
             "automaton; plans timed, restarts rebuild the raster untimed)";
         Scenario s = make_factory_floor_scenario(in.floor50(), 0);
         s.robot().controller.planner.kind = PlannerKind::AStar;
         s.robot().controller.planner.cell_size = 0.1;  // 200 x 200 planning cells
         time_stepping(s, in.budget, r);
       }},
      {"lidar180_50_polygons",
       [&in](CaseResult& r) {
         r.what = "TurtleBot3 base, 180-beam 360-degree lidar (3.5 m), same floor";
         time_stepping(make_factory_floor_scenario(in.floor50(), 180), in.budget, r);
       }},
      {"lidar360_aws_warehouse",
       [&in](CaseResult& r) {
         r.what = "TurtleBot3 Burger, 360-beam lidar, AWS small warehouse map (0.05 m cells)";
         const std::optional<Scenario> s =
             in.maps_dir.empty() ? std::nullopt : make_aws_scenario(in.maps_dir);
         if (!s) {
           r.skipped = "AWS warehouse map not found (data/maps: run from the repository)";
           return;
         }
         time_stepping(*s, in.budget, r);
       }},
      {"fleet_100x_lidar180_50_polygons",
       [&in](CaseResult& r) {
         r.what = "100 180-beam lidar robots sensing each other on the 50-polygon floor, all cores";
         time_fleet(make_fleet_scenario(in.floor50(), kFleetRobots, 180), 0, in.budget, r);
       }},
      {"fleet_1000x_quickbot_warehouse",
       [&in](CaseResult& r) {
         r.what = "1,000 QuickBots (5 IR) sensing each other, 63 x 63 m warehouse, all cores";
         time_fleet(make_fleet_scenario(std::make_shared<const World>(make_fleet_warehouse(1000)),
                                        1000, 0),
                    0, in.budget, r);
       }},
      {"fleet_100000x_quickbot_warehouse",
       [&in](CaseResult& r) {
         r.what = "100,000 QuickBots (5 IR) sensing each other, 632 x 632 m warehouse, all cores";
         time_fleet(make_fleet_scenario(std::make_shared<const World>(make_fleet_warehouse(100000)),
                                        100000, 0),
                    0, in.budget, r);
       }},
      {"run_factory_delivery",
       [&in](CaseResult& r) {
         r.what = "whole run of scenarios/factory_delivery.yaml (QuickBot, trajectory kept)";
         std::optional<Scenario> s;
         if (in.scenario_dir.empty())
           s = load_scenario_text(app::kDemoScenarioYaml, "factory-delivery.yaml");
         else
           s = in.scenario_file("factory_delivery.yaml", r);
         time_runs(*s, in.budget, r);
       }},
      {"run_rectangle",
       [&in](CaseResult& r) {
         r.what = "whole run of scenarios/rectangle.yaml (QuickBot, trajectory kept)";
         const std::optional<Scenario> s = in.scenario_file("rectangle.yaml", r);
         if (s) time_runs(*s, in.budget, r);
       }},
  };
}

/// Runs the cases whose name contains `filter` (all when it is empty), in order.
std::vector<CaseResult> run_cases(const std::vector<Case>& cases, const std::string& filter) {
  std::vector<CaseResult> results;
  for (const Case& c : cases) {
    if (!filter.empty() && c.name.find(filter) == std::string::npos) continue;
    CaseResult r;
    r.name = c.name;
    c.run(r);
    results.push_back(r);
  }
  return results;
}

/// One case's measures as `--json` writes them.
nlohmann::json case_json(const CaseResult& r) {
  nlohmann::json j = {{"name", r.name}, {"what", r.what}};
  if (!r.skipped.empty()) {
    j["skipped"] = r.skipped;
    return j;
  }
  j["robots"] = r.robots;
  j["robot_steps"] = r.robot_steps;
  j["seconds"] = r.seconds;
  j["robot_steps_per_s"] = r.steps_per_second();
  j["world_steps_per_s"] = r.steps_per_second() / r.robots;
  j["rays_per_step"] = r.rays_per_step;
  j["rays_per_s"] = r.steps_per_second() * r.rays_per_step;
  j["ns_per_step"] = r.ns_per_step();
  if (r.runs > 0) {
    j["runs"] = r.runs;
    j["ms_per_run"] = 1e3 * r.seconds / static_cast<double>(r.runs);
  } else {
    j["restarts"] = r.restarts;
  }
  return j;
}

void print_json(const std::vector<CaseResult>& results, double budget) {
  nlohmann::json out;
  out["machine"] = {{"cpu", cpu_model()},
                    {"cores", std::thread::hardware_concurrency()},
                    {"compiler", compiler()},
                    {"build", build_type()},
                    {"date", utc_date()}};
  out["seconds_per_case"] = budget;
  out["cases"] = nlohmann::json::array();
  for (const CaseResult& r : results) out["cases"].push_back(case_json(r));
  fmt::print("{}\n", out.dump(2));
}

void print_table(const std::vector<CaseResult>& results, double budget) {
  fmt::print(
      "floornav bench: {} ({} cores), {}, {}; one thread (fleets: all cores), ~{:g} s per case\n",
      cpu_model(), std::thread::hardware_concurrency(), compiler(), build_type(), budget);
  fmt::print("{:<34} {:>15} {:>15} {:>10}  {}\n", "case", "robot-steps/s", "rays/s", "ns/step",
             "notes");
  for (const CaseResult& r : results) {
    if (!r.skipped.empty()) {
      fmt::print("{:<34} {:>15} {:>15} {:>10}  skipped: {}\n", r.name, "-", "-", "-", r.skipped);
      continue;
    }
    std::string notes;
    if (r.robots > 1)
      notes = fmt::format("{} robots: {} world-steps/s", r.robots,
                          grouped(r.steps_per_second() / r.robots));
    else if (r.runs > 0)
      notes = fmt::format("{:.2f} ms per run of {} steps", 1e3 * r.seconds / r.runs,
                          r.robot_steps / r.runs);
    fmt::print("{:<34} {:>15} {:>15} {:>10.0f}  {}\n", r.name, grouped(r.steps_per_second()),
               grouped(r.steps_per_second() * r.rays_per_step), r.ns_per_step(), notes);
  }
}

}  // namespace

int run_bench(const BenchOptions& options) {
  if (!(options.seconds_per_case > 0.0)) {
    fmt::print(stderr, "floornav: error: --seconds must be positive, got {}\n",
               options.seconds_per_case);
    return 2;
  }
  BenchInputs inputs(options);
  const std::vector<Case> cases = standard_cases(inputs);
  const std::vector<CaseResult> results = run_cases(cases, options.filter);
  if (results.empty()) {
    std::string names;
    for (const Case& c : cases) names += (names.empty() ? "" : ", ") + c.name;
    fmt::print(stderr, "floornav: error: --filter '{}' matches no case (cases: {})\n",
               options.filter, names);
    return 2;
  }
  if (options.json)
    print_json(results, inputs.budget);
  else
    print_table(results, inputs.budget);
  return 0;
}

}  // namespace floornav
