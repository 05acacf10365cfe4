#pragma once
// The scenario's moving obstacles: `people:`, `people_file:` (HuNavSim agent files) and
// `forklifts:`. Private to the io library.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "floornav/scenario/random_people.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/crowd.hpp"
#include "yaml_reader.hpp"

namespace floornav::io_detail {

/// Reads the top-level crowd keys of a scenario (if present) into `crowd`; paths are relative to
/// the scenario file `origin`. A people_file read is appended to `files_read`.
void read_crowd(const std::string& file, MapReader& top, const std::filesystem::path& origin,
                CrowdSpec& crowd, std::vector<std::string>& files_read);

/// The `random_people:` section, if given: its keys read and checked (ranges, units).
std::optional<RandomPeopleSpec> read_random_people(const std::string& file, MapReader& top);

/// Places the people `spec` asks for on the scenario's world (which must be built) from its
/// sim.seed, after the people it already has; an error on `random_people.density` when the floor
/// cannot hold them.
void add_random_people(const std::string& file, const YAML::Node& root,
                       const RandomPeopleSpec& spec, Scenario& s);

/// The people of a HuNavSim agent file (a ROS 2 parameter file, `hunav_loader:
/// ros__parameters: agents: [...]`): each agent's init_pose, goals (in order), max_vel as the
/// walking speed, radius, goal_radius and cyclic_goals. HuNavSim's behaviours (curious, scared,
/// ...) are not modelled: every agent walks by the social force model. Read as strictly as a
/// scenario: one YAML document, every key known (HuNavSim's own that floornav does not use, such
/// as `behavior`, are known), no key twice, every agent listed once, at most 1000 goals per agent.
/// Errors name the file and the key.
std::vector<PersonSpec> load_hunav_agents(const std::filesystem::path& path);

}  // namespace floornav::io_detail
