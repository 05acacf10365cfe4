// HuNavSim agent files (a scenario's people_file) and the crowd they make. Input: the agent
// file's bytes, written as agents.yaml beside a fixed scenario that names it (an empty hall, one
// robot); what loads is simulated for up to 20 steps as a crowd: every person's position, heading
// and path length stay finite.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace floornav;

constexpr std::string_view kScenario =
    "name: hunav\n"
    "world: {bounds: [-30, -30, 30, 30]}\n"
    "people_file: agents.yaml\n"
    "robot: {preset: quickbot, start: [-25, -25, 0]}\n"
    "goal: [-24, -25]\n"
    "sim: {dt: 0.05, t_max: 1}\n";

void check_crowd(const Scenario& loaded) {
  Scenario s = loaded;
  s.sim.t_max = std::min(s.sim.t_max, 20.0 * s.sim.dt);
  s.sim.record_trajectory = true;
  fuzz::check_crowd(simulate_fleet(s).crowd);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view agents(reinterpret_cast<const char*>(data), size);
  fuzz::write_scratch("agents.yaml", agents);
  try {
    check_crowd(load_scenario_text(kScenario, fuzz::scratch_dir() / "hunav.yaml"));
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
