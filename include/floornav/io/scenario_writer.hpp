#pragma once
/// @file
/// A scenario written back as scenario keys: the run's resolved configuration, after presets and
/// every override, with every value explicit (the preset's robot and controller values too). It is
/// what `config` holds in summary.json and in each batch line, and what `floornav run
/// --config-out FILE` writes: loading it gives back an equal scenario (the same world, robots,
/// controllers and sim settings, bit for bit), so the run can be repeated from it alone.
///
/// What it cannot say: a world's map is named by its file (WorldMapSource; a grid built in code
/// has none and is left out), a user's own controller (a ControllerFactory) only by its kind, and
/// sensors that differ in their ranges or cones within one robot only as the first one's (a
/// scenario file cannot express them either).

#include <string>

#include <nlohmann/json.hpp>

#include "floornav/scenario/scenario.hpp"

namespace floornav {

/// The scenario as a JSON object of scenario keys: name, world, robot + goal/goals (a lone robot)
/// or robots (a list), controller, sim. Numbers are exact (shortest text that reads back to the
/// same double).
nlohmann::ordered_json scenario_to_json(const Scenario& scenario);

/// The same as a YAML scenario file, with a comment line saying what it is.
std::string scenario_to_yaml(const Scenario& scenario);

/// JSON (as scenario_to_json gives it) as YAML text: mappings in block style, lists of numbers
/// and of points in flow style, every string double-quoted.
std::string json_to_yaml(const nlohmann::ordered_json& value);

}  // namespace floornav
