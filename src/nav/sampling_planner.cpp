#include "floornav/nav/sampling_planner.hpp"

#include <atomic>

namespace floornav {

namespace {
// Constant-initialised (before any static constructor runs), so floornav::ompl's installer may
// run in any order with the rest of the program's start-up.
std::atomic<SampledPathSearch> g_rrt_connect{nullptr};
}  // namespace

SampledPathSearch rrt_connect_search() {
  return g_rrt_connect.load(std::memory_order_acquire);
}

void set_rrt_connect_search(SampledPathSearch search) {
  g_rrt_connect.store(search, std::memory_order_release);
}

}  // namespace floornav
