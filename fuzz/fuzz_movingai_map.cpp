// MovingAI .map grids (load_movingai_map). Input: the file's bytes.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "floornav/io/movingai_map.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floornav;
  const auto path =
      fuzz::write_scratch("grid.map", std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    const OccupancyGrid g = load_movingai_map(path, 0.5);
    if (g.width() <= 0 || g.height() <= 0) fuzz::finding("an empty grid was accepted");
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
