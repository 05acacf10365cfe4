#include "world_map.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "floornav/core/input_error.hpp"
#include "floornav/io/course_world.hpp"
#include "floornav/io/movingai_map.hpp"
#include "floornav/io/ros_map.hpp"
#include "floornav/io/sdf_world.hpp"
#include "input_file.hpp"

namespace floornav::io_detail {

std::shared_ptr<const OccupancyGrid> load_world_map(const std::filesystem::path& path,
                                                    const MapOptions& options, WorldDesc& desc,
                                                    const std::string& scenario_file,
                                                    const std::string& key,
                                                    std::vector<std::string>& files_read) {
  // Named for what it is (missing, a folder, a FIFO, a device) before any reader opens it.
  if (auto problem = input_file_problem(path, "map", std::uint64_t{1} << 40))
    throw InputError(scenario_file, key, fmt::format("map file '{}' {}", path.string(), *problem));
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  files_read.push_back(path.string());
  if (ext == ".yaml" || ext == ".yml") {
    RosMapOptions ro;
    ro.unknown = options.unknown_is_occupied ? UnknownPolicy::Occupied : UnknownPolicy::Free;
    std::filesystem::path image;
    auto grid = std::make_shared<const OccupancyGrid>(load_ros_map(path, ro, &image));
    files_read.push_back(image.string());
    return grid;
  }
  if (ext == ".pgm" || ext == ".png") {
    if (options.cell_size <= 0.0)
      throw InputError(scenario_file, key,
                       "an image map without a yaml needs world.cell_size (metres per pixel)");
    RosMapOptions ro;
    ro.unknown = options.unknown_is_occupied ? UnknownPolicy::Occupied : UnknownPolicy::Free;
    return std::make_shared<const OccupancyGrid>(load_ros_image_map(path, options.cell_size, ro));
  }
  if (ext == ".map") {
    if (options.cell_size <= 0.0)
      throw InputError(scenario_file, key,
                       "a MovingAI .map needs world.cell_size (metres per cell)");
    return std::make_shared<const OccupancyGrid>(load_movingai_map(path, options.cell_size));
  }
  if (ext == ".world" || ext == ".sdf") {
    SdfWorld w = load_sdf_world(path);
    if (!w.skipped.empty()) {
      // What the world holds but floornav cannot read would be an obstacle the robot drives
      // through: refused, never dropped.
      const std::string& first = w.skipped.front();  // "line 12: what"
      const auto colon = first.find(": ");
      const bool has_line = first.rfind("line ", 0) == 0 && colon != std::string::npos;
      throw InputError(path.string(), has_line ? first.substr(0, colon) : "",
                       (has_line ? first.substr(colon + 2) : first) +
                           (w.skipped.size() > 1
                                ? fmt::format(" (and {} more such things)", w.skipped.size() - 1)
                                : std::string()));
    }
    desc.circles.insert(desc.circles.end(), w.circles.begin(), w.circles.end());
    for (auto& p : w.polygons) desc.polygons.push_back(std::move(p));
    return nullptr;
  }
  if (ext == ".xml") {
    CourseWorld w = load_course_world(path);
    for (auto& p : w.obstacles) desc.polygons.push_back(std::move(p));
    return nullptr;
  }
  throw InputError(scenario_file, key,
                   fmt::format("unknown map format '{}' (expected a ROS .yaml, .pgm/.png with "
                               "cell_size, MovingAI .map, Gazebo .world/.sdf or course .xml)",
                               ext));
}

}  // namespace floornav::io_detail
