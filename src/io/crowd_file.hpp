#pragma once
// The scenario's moving obstacles: `people:`, `people_file:` (HuNavSim agent files) and
// `forklifts:`. Private to the io library.

#include <filesystem>

#include "floornav/sim/crowd.hpp"
#include "yaml_reader.hpp"

namespace floornav::io_detail {

/// Reads the top-level crowd keys of a scenario (if present) into `crowd`; paths are relative to
/// the scenario file `origin`.
void read_crowd(const std::string& file, MapReader& top, const std::filesystem::path& origin,
                CrowdSpec& crowd);

/// The people of a HuNavSim agent file (a ROS 2 parameter file, `hunav_loader:
/// ros__parameters: agents: [...]`): each agent's init_pose, goals (in order), max_vel as the
/// walking speed, radius, goal_radius and cyclic_goals. HuNavSim's behaviours (curious, scared,
/// ...) are not modelled: every agent walks by the social force model. Errors name the file and
/// the key.
std::vector<PersonSpec> load_hunav_agents(const std::filesystem::path& path);

}  // namespace floornav::io_detail
