#pragma once
/// @file
/// Scenario files (YAML) -> Scenario, strictly: unknown keys, wrong types, non-finite or
/// out-of-range values and impossible set-ups are errors naming the file, the line and the
/// dotted key. `--set KEY=VALUE` overrides are applied to the YAML tree before it is read.

#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/scenario/validate.hpp"

namespace floornav {

/// A value set from outside the scenario file, as `--set` does: `assignment` is "dotted.key=VALUE"
/// (VALUE is YAML). An error about the key names `file` and `where` instead of the scenario file:
/// the user's --set is file "" and where "--set KEY=VALUE"; a value that a batch source sets
/// names that source (the .scen file and its line).
struct ScenarioOverride {
  std::string assignment;
  std::string file;
  std::string where;
  /// VALUE is text set as a string node as it stands (a path a batch source sets), never read as
  /// YAML: a '#', ': ' or quote in it is part of the text, not a comment or a mapping.
  bool text{false};
};

/// The user's `--set` values as overrides that errors blame on their `--set`.
std::vector<ScenarioOverride> user_overrides(std::span<const std::string> sets);

/// Loads and validates the scenario in `path`, after applying the --set values `overrides`
/// ("a.b=value").
Scenario load_scenario_file(const std::filesystem::path& path,
                            std::span<const std::string> overrides = {});

/// The same from YAML text; `origin` names it in errors and anchors relative paths.
Scenario load_scenario_text(std::string_view yaml, const std::filesystem::path& origin,
                            std::span<const std::string> overrides = {});

/// load_scenario_file with overrides from any source (see ScenarioOverride), applied in order.
Scenario load_scenario_with_overrides(const std::filesystem::path& path,
                                      std::span<const ScenarioOverride> overrides);
Scenario load_scenario_text_with_overrides(std::string_view yaml,
                                           const std::filesystem::path& origin,
                                           std::span<const ScenarioOverride> overrides);

/// The limits a scenario file is held to (docs/SCENARIOS.md, "Limits"), checked before anything
/// is allocated for what they bound.
inline constexpr std::size_t kMaxRobots = 100000;
inline constexpr std::size_t kMaxGoalsPerRobot = 10000;
inline constexpr std::size_t kMaxGoalsInAll = 1000000;
inline constexpr std::size_t kMaxSensorsPerRobot = 4096;
/// Rays one robot casts per step: sensors times their cone_rays.
inline constexpr std::size_t kMaxRaysPerRobot = 4096;
/// Rays a whole fleet casts per step.
inline constexpr std::size_t kMaxRaysInAll = 20000000;
/// Robots times people and forklifts (each pair is checked every step).
inline constexpr std::size_t kMaxRobotMoverPairs = 10000000;

}  // namespace floornav
