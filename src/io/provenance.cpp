#include "floornav/io/provenance.hpp"

#include <string_view>

#include "floornav/io/scenario_writer.hpp"
#include "floornav_version.hpp"  // generated at configure time

namespace floornav {

std::string floornav_version() {
  const std::string_view commit = io_detail::kGitCommit;
  return std::string(io_detail::kProjectVersion) + (commit.empty() || commit == "unknown"
                                                        ? std::string("+unknown")
                                                        : "+git." + std::string(commit));
}

nlohmann::ordered_json provenance_json(const Scenario& scenario,
                                       std::span<const std::string> overrides) {
  nlohmann::ordered_json j = nlohmann::ordered_json::object();
  j["floornav_version"] = floornav_version();
  j["seed"] = scenario.sim.seed;
  j["overrides"] = nlohmann::ordered_json::array();
  for (const std::string& o : overrides) j["overrides"].push_back(o);
  j["config"] = scenario_to_json(scenario);
  return j;
}

}  // namespace floornav
