#pragma once
/// @file
/// Scenario files (YAML) -> Scenario, strictly: unknown keys, wrong types, non-finite or
/// out-of-range values and impossible set-ups are errors naming the file, the line and the
/// dotted key. `--set KEY=VALUE` overrides are applied to the YAML tree before it is read.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>

#include "floornav/io/input_error.hpp"
#include "floornav/scenario/scenario.hpp"

namespace floornav {

/// Loads and validates the scenario in `path`, after applying `overrides` ("a.b=value").
Scenario load_scenario_file(const std::filesystem::path& path,
                            std::span<const std::string> overrides = {});

/// The same from YAML text; `origin` names it in errors and anchors relative paths.
Scenario load_scenario_text(std::string_view yaml, const std::filesystem::path& origin,
                            std::span<const std::string> overrides = {});

/// Checks a scenario built in code or loaded: start and goals in free space, sane step, ...
/// Throws InputError naming `file` and the key.
void validate_scenario(const Scenario& s, const std::string& file);

}  // namespace floornav
