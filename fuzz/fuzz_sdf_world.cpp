// Gazebo SDF worlds (load_sdf_world). Input: the file's bytes.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "floornav/io/sdf_world.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floornav;
  const auto path =
      fuzz::write_scratch("world.sdf", std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    const SdfWorld w = load_sdf_world(path);
    for (const Circle& c : w.circles) {
      fuzz::check_finite(c.center, "cylinder centre");
      if (!(c.radius > 0.0) || !std::isfinite(c.radius)) fuzz::finding("a bad radius was accepted");
    }
    for (const auto& poly : w.polygons) {
      if (poly.size() < 3) fuzz::finding("a box of fewer than 3 corners");
      for (const Vec2& p : poly) fuzz::check_finite(p, "box corner");
    }
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
