#pragma once
/// @file
/// ROS map_server maps: a yaml file naming a PGM or PNG image, read into an OccupancyGrid with
/// map_server's own rules (ROS 1 `map_server/src/image_loader.cpp`, ROS 2 `nav2_map_server`).

#include <filesystem>

#include "floornav/world/occupancy_grid.hpp"

namespace floornav {

/// What a cell between `free_thresh` and `occupied_thresh` (map_server's "unknown", -1) becomes.
enum class UnknownPolicy {
  Occupied,  ///< unknown space is not known to be free: the careful choice, the default
  Free,      ///< trust only what is marked occupied
};

/// Options of our own, on top of what the yaml says.
struct RosMapOptions {
  UnknownPolicy unknown{UnknownPolicy::Occupied};  ///< cells between the thresholds
};

/// Loads a map_server yaml: `image` (PGM or PNG, relative to the yaml's folder unless absolute),
/// `resolution` (m/cell, > 0), `origin` [x, y, yaw] (the lower-left corner of the image, m and
/// rad), `negate` (0/1 or a bool), `occupied_thresh` and `free_thresh` (in [0, 1]), optional
/// `mode` (trinary, the default; scale; raw). Each pixel's channel mean v (0..255, alpha ignored)
/// gives p = (255 - v) / 255 (v / 255 when negated): occupied if p > occupied_thresh, free if
/// p < free_thresh, else unknown. In raw mode the value v itself is the occupancy in percent
/// (0..100, larger values unknown), thresholded the same way. Image row 0 becomes the grid's top
/// row. Unknown keys are ignored, as map_server does. Throws InputError naming the file and the
/// line or key at fault. With `image_read`, the image file's path (as resolved) is put there.
OccupancyGrid load_ros_map(const std::filesystem::path& yaml, const RosMapOptions& options = {},
                           std::filesystem::path* image_read = nullptr);

/// Loads an image without a yaml as the old `map_server <image> <resolution>` did (e.g. the
/// Willow Garage floor plans): origin (0, 0, 0), negate 0, occupied_thresh 0.65,
/// free_thresh 0.196, trinary mode. Throws InputError.
OccupancyGrid load_ros_image_map(const std::filesystem::path& image, double resolution,
                                 const RosMapOptions& options = {});

}  // namespace floornav
