// Scenario YAML text (load_scenario_text) and --set overrides, then a few steps of the simulation
// of what loaded (a fleet and its people and forklifts as a fleet). Input: the YAML text, then
// optionally a NUL byte and one --set KEY=VALUE per line.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/simulation.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace floornav;

void check_run(const RunResult& r) {
  for (const TrajectorySample& p : r.trajectory) {
    for (const double v : {p.t, p.x, p.y, p.theta, p.v, p.omega, p.w_left, p.w_right})
      fuzz::check_finite(v, "trajectory value");
  }
  fuzz::check_finite(r.path_length, "path length");
  fuzz::check_finite(r.sim_time, "simulated time");
  if (std::isnan(r.min_clearance)) fuzz::finding("min_clearance is NaN");
}

/// Runs at most 20 steps and checks that every number the run reports is finite: a lone robot
/// alone, else (a robots list, people, forklifts) the fleet with its crowd.
void simulate_briefly(Scenario s) {
  std::size_t sensors = 0;
  for (const RobotTask& t : s.robots) sensors += t.robot.sensors.size();
  if (sensors > 1024 || s.robots.size() > 64 ||
      s.crowd.people.size() + s.crowd.forklifts.size() > 256)
    return;  // valid, but too slow to be worth a fuzzer's time
  s.sim.t_max = std::min(s.sim.t_max, 20.0 * s.sim.dt);
  if (!s.is_fleet() && s.crowd.people.empty() && s.crowd.forklifts.empty()) {
    check_run(simulate(s));
    return;
  }
  const FleetResult f = simulate_fleet(s);
  for (const RunResult& r : f.robots) check_run(r);
  fuzz::check_crowd(f.crowd);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string_view yaml = input.substr(0, nul);
  std::vector<std::string> overrides;
  if (nul != std::string_view::npos) {
    std::string_view rest = input.substr(nul + 1);
    while (!rest.empty()) {
      const std::size_t eol = rest.find('\n');
      overrides.emplace_back(rest.substr(0, eol));
      rest = eol == std::string_view::npos ? std::string_view() : rest.substr(eol + 1);
    }
  }
  try {
    // A folder that does not exist: relative world.map paths find nothing.
    simulate_briefly(load_scenario_text(yaml, "/nonexistent/fuzz.yaml", overrides));
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
