#pragma once
/// @file
/// Scenario files (YAML) -> Scenario, strictly: unknown keys, wrong types, non-finite or
/// out-of-range values and impossible set-ups are errors naming the file, the line and the
/// dotted key. `--set KEY=VALUE` overrides are applied to the YAML tree before it is read.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "floornav/core/input_error.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/scenario/validate.hpp"

namespace floornav {

/// Loads and validates the scenario in `path`, after applying `overrides` ("a.b=value").
Scenario load_scenario_file(const std::filesystem::path& path,
                            std::span<const std::string> overrides = {});

/// The same from YAML text; `origin` names it in errors and anchors relative paths.
Scenario load_scenario_text(std::string_view yaml, const std::filesystem::path& origin,
                            std::span<const std::string> overrides = {});

}  // namespace floornav
