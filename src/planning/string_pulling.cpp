#include "floornav/planning/string_pulling.hpp"

#include "floornav/planning/line_of_sight.hpp"

namespace floornav {

std::vector<Vec2> pull_string(const FreeRaster& raster, std::span<const Vec2> points) {
  std::vector<Vec2> out;
  pull_string(
      points, [&](const Vec2& a, const Vec2& b) { return line_of_sight(raster, a, b); }, out);
  return out;
}

}  // namespace floornav
