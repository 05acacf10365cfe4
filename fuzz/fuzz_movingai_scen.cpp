// MovingAI .scen case lists (load_movingai_scen). Input: the file's bytes.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "floornav/io/movingai_map.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floornav;
  const auto path = fuzz::write_scratch(
      "cases.scen", std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    for (const MovingAiCase& c : load_movingai_scen(path)) {
      if (c.start_x < 0 || c.start_x >= c.width || c.start_y < 0 || c.start_y >= c.height ||
          c.goal_x < 0 || c.goal_x >= c.width || c.goal_y < 0 || c.goal_y >= c.height)
        fuzz::finding("a case outside its map was accepted");
      fuzz::check_finite(c.optimal_length, "optimal length");
    }
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
