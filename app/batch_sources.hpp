#pragma once
// Where batch cases come from besides plain scenario files: a MovingAI .scen file, or a folder of
// Gazebo worlds (BARN), each with a template scenario.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "floornav/runner/batch.hpp"

namespace floornav {

std::vector<BatchCase> make_scen_cases(const std::string& template_file,
                                       const std::string& scen_file, double cell_size,
                                       std::span<const std::string> overrides);

/// One case per .world/.sdf file in `dir` (in natural order: world_2 before world_10), with the
/// template's robot, controller, start and goal. With `barn_paths`, each world_N also gets the
/// BARN optimal time from path_N.npy.
std::vector<BatchCase> make_world_cases(const std::string& template_file, const std::string& dir,
                                        const std::string& barn_paths,
                                        std::span<const std::string> overrides);

/// `count` generated factory floors (bench_cases.hpp: a walled 20 x 20 m hall of 50 random
/// star-shaped obstacles, floor seed `first_seed + i`), each with a tour of four goals across
/// it drawn from that seed; robot, controller and sim from the template (its world, start and
/// goals are replaced).
std::vector<BatchCase> make_floor_cases(const std::string& template_file, int count,
                                        std::uint64_t first_seed,
                                        std::span<const std::string> overrides);

}  // namespace floornav
