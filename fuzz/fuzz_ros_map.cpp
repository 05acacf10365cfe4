// ROS map_server maps: the map yaml and its image (PGM or PNG). Input: the yaml text, a NUL byte,
// then the image's bytes, written as map.yaml and map.pgm (the reader goes by the bytes, not the
// name). Both load_ros_map (yaml + image) and load_ros_image_map (the image alone) run.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "floornav/io/ros_map.hpp"
#include "fuzz_support.hpp"

namespace {

using namespace floornav;

void check_grid(const OccupancyGrid& g) {
  if (g.width() <= 0 || g.height() <= 0) fuzz::finding("an empty grid was accepted");
  fuzz::check_finite(g.resolution(), "resolution");
  fuzz::check_finite(g.origin().position, "origin");
  fuzz::check_finite(g.origin().theta, "origin yaw");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string_view yaml = input.substr(0, nul);
  const std::string_view image =
      nul == std::string_view::npos ? std::string_view() : input.substr(nul + 1);
  const auto yaml_path = fuzz::write_scratch("map.yaml", yaml);
  const auto image_path = fuzz::write_scratch("map.pgm", image);
  try {
    check_grid(load_ros_map(yaml_path));
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  try {
    check_grid(load_ros_image_map(image_path, 0.05));
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
