#pragma once
/// @file
/// MovingAI grid benchmarks (movingai.com/benchmarks): `.map` grids and `.scen` scenario lists.

#include <filesystem>
#include <string>
#include <vector>

#include "floornav/geometry/vec2.hpp"
#include "floornav/world/occupancy_grid.hpp"

namespace floornav {

/// Loads a MovingAI `.map` ("type octile", "height H", "width W", "map", then H rows of W
/// characters, row 0 at the top). '.', 'G' and 'S' are free; '@', 'O', 'T' and 'W' are blocked;
/// any other character is an error (never silently a wall).
/// Each character becomes a `cell_size` (m) square; the grid's origin (0, 0) is the map's
/// lower-left corner, so MovingAI row y is grid row H - 1 - y. Throws InputError naming the line.
OccupancyGrid load_movingai_map(const std::filesystem::path& map, double cell_size);

/// One line of a `.scen` file. Coordinates are MovingAI cells: x = column, y = row from the top.
struct MovingAiCase {
  int line{0};           ///< the line of the .scen file it is on (from 1)
  int bucket{0};         ///< floor(optimal_length / 4)
  std::string map_file;  ///< the `.map` it refers to, as written
  int width{0};          ///< map width (cells)
  int height{0};         ///< map height (cells)
  int start_x{0};
  int start_y{0};
  int goal_x{0};
  int goal_y{0};
  double optimal_length{0.0};  ///< octile distance in cells (diagonal sqrt 2, no corner cutting)
};

/// The most rows a `.scen` file may hold (MovingAI's own hold a few thousand).
inline constexpr std::size_t kMaxScenRows = 1000000;

/// Loads a `.scen` file: "version 1" (or "version 1.0"), then one case per line with 9
/// tab-separated fields, at most kMaxScenRows. Blank lines are skipped. Throws InputError naming
/// the line and field.
std::vector<MovingAiCase> load_movingai_scen(const std::filesystem::path& scen);

/// World-frame centre (m) of MovingAI cell (x, y) (y counted from the top) in a grid loaded by
/// load_movingai_map with this `height` and `cell_size`.
inline Vec2 movingai_cell_center(int x, int y, int height, double cell_size) {
  return {(x + 0.5) * cell_size, (height - 1 - y + 0.5) * cell_size};
}

}  // namespace floornav
