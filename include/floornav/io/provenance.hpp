#pragma once
/// @file
/// What produced a run, written into every summary.json and every batch line so that a number
/// can be traced to the exact build, scenario and overrides behind it.

#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "floornav/scenario/scenario.hpp"

namespace floornav {

/// "0.1.0+git.<commit>" for a build configured from a git checkout (the commit's 40 hex
/// digits), "0.1.0+unknown" otherwise.
std::string floornav_version();

/// The provenance keys, in this order: `floornav_version`, `seed` (sim.seed), `overrides` (the
/// --set values as given, in order) and `config` (the resolved scenario, scenario_to_json: what
/// load_scenario_file would rebuild the run from).
nlohmann::ordered_json provenance_json(const Scenario& scenario,
                                       std::span<const std::string> overrides);

}  // namespace floornav
