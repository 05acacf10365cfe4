// Sim.I.Am / pySimiam course worlds (load_course_world). Input: the file's bytes.

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "floornav/geometry/polygon.hpp"
#include "floornav/io/course_world.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace floornav;
  const auto path =
      fuzz::write_scratch("world.xml", std::string_view(reinterpret_cast<const char*>(data), size));
  try {
    const CourseWorld w = load_course_world(path);
    for (const CourseRobot& r : w.robots) {
      fuzz::check_finite(r.pose.position, "robot position");
      fuzz::check_finite(r.pose.theta, "robot heading");
    }
    for (const auto& poly : w.obstacles) {
      for (const Vec2& p : poly) fuzz::check_finite(p, "obstacle point");
      if (!is_simple(poly)) fuzz::finding("a polygon that is not simple was accepted");
    }
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
