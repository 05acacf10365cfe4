#pragma once
// Loads the `world.map` of a scenario (ROS map_server yaml, MovingAI .map, Gazebo .world/.sdf,
// course-simulator .xml) into the world description. Private to the io library.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav::io_detail {

struct MapOptions {
  double cell_size{0.0};           ///< m per cell for MovingAI maps (required there)
  bool unknown_is_occupied{true};  ///< ROS maps: cells between the thresholds
};

/// Adds what `path` holds to `desc`; returns the occupancy grid if the map is one (the caller
/// keeps it alive). Appends every file it read (the map, a map yaml's image) to `files_read`.
/// Throws InputError naming `path` (or `scenario_file` + `key` for a bad option).
std::shared_ptr<const OccupancyGrid> load_world_map(const std::filesystem::path& path,
                                                    const MapOptions& options, WorldDesc& desc,
                                                    const std::string& scenario_file,
                                                    const std::string& key,
                                                    std::vector<std::string>& files_read);

}  // namespace floornav::io_detail
