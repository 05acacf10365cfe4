#pragma once
// Private to src/io: the world as an occupancy grid, for run.mcap's /map (nav_msgs/msg/
// OccupancyGrid): a map world's own cells (unknown -1, occupied 100, free 0) with its shapes
// marked on top, or a world of shapes rasterised at 0.05 m over its extent (twice as coarse,
// and again, while that passes a million cells); a cell is occupied when its centre is.

#include <cstdint>
#include <vector>

#include "floornav/geometry/pose2.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

struct WorldRaster {
  double resolution{0.05};  ///< m per cell
  int width{1}, height{1};
  Pose2 origin{};                  ///< the corner of cell (0, 0)
  std::vector<std::int8_t> cells;  ///< row-major from row 0 at the origin
};

WorldRaster world_raster(const World& world);

}  // namespace floornav
