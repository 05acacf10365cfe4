// The hot loop allocates nothing (STYLE.md point 10): after a warm-up, Simulation::step() calls
// the global operator new zero times. This file replaces the global operator new/delete for the
// whole test executable; the replacements count only while a test window is open on this thread
// and otherwise just forward to malloc/free.
#include <gtest/gtest.h>

#include <filesystem>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/simulation.hpp"

namespace {

thread_local bool t_counting = false;
std::atomic<long> g_allocations{0};

void* allocate(std::size_t size) {
  if (t_counting) g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (size == 0) size = 1;
  return std::malloc(size);
}

void* allocate_aligned(std::size_t size, std::align_val_t align) {
  if (t_counting) g_allocations.fetch_add(1, std::memory_order_relaxed);
  const auto a = static_cast<std::size_t>(align);
  const std::size_t rounded = (size + a - 1) / a * a;  // aligned_alloc wants a multiple
  return std::aligned_alloc(a, rounded == 0 ? a : rounded);
}

/// Counts the allocations made by this thread while it lives.
class AllocationWindow {
 public:
  AllocationWindow() {
    g_allocations.store(0);
    t_counting = true;
  }
  ~AllocationWindow() { t_counting = false; }
  long count() const { return g_allocations.load(); }
};

}  // namespace

// These replace the global allocation functions with malloc/free on purpose; GCC's inliner then
// sees a new paired with free and warns, which is exactly what a replacement does.
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"

void* operator new(std::size_t size) {
  if (void* p = allocate(size)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  if (void* p = allocate(size)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  return allocate(size);
}
void* operator new[](std::size_t size, const std::nothrow_t&) noexcept {
  return allocate(size);
}
void* operator new(std::size_t size, std::align_val_t align) {
  if (void* p = allocate_aligned(size, align)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t size, std::align_val_t align) {
  if (void* p = allocate_aligned(size, align)) return p;
  throw std::bad_alloc();
}
void* operator new(std::size_t size, std::align_val_t align, const std::nothrow_t&) noexcept {
  return allocate_aligned(size, align);
}
void* operator new[](std::size_t size, std::align_val_t align, const std::nothrow_t&) noexcept {
  return allocate_aligned(size, align);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete(void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept {
  std::free(p);
}
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept {
  std::free(p);
}

namespace floornav {
namespace {

constexpr int kWarmUpSteps = 100;
constexpr int kCountedSteps = 1000;

struct WindowResult {
  long allocations{0};
  int switches{0};  ///< mode switches inside the counted window
};

/// Warms a simulation of `file` (with `sets`) up, then counts the allocations of 1000 steps.
/// The run must still be going at the end, so that every counted step did real work.
WindowResult count_step_allocations(const std::string& file, std::vector<std::string> sets) {
  Scenario s = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + file, sets);
  s.sim.record_trajectory = false;
  Simulation sim = make_simulation(s);
  for (int i = 0; i < kWarmUpSteps; ++i) EXPECT_TRUE(sim.step());
  const int switches_before = sim.result().mode_switches;
  WindowResult out;
  bool running = true;
  {
    const AllocationWindow window;
    for (int i = 0; i < kCountedSteps; ++i) running = sim.step() && running;
    out.allocations = window.count();
  }
  EXPECT_TRUE(running) << file << " ended inside the counted window";
  out.switches = sim.result().mode_switches - switches_before;
  return out;
}

TEST(Allocation, TheCounterSeesAllocations) {
  long count = 0;
  {
    const AllocationWindow window;
    // A direct call: unlike a new-expression, the compiler may not elide it.
    void* p = ::operator new(64);
    ::operator delete(p);
    count = window.count();
  }
  EXPECT_EQ(count, 1);
}

// The QuickBot (5 IR sensors, obstacle memory) on the factory floor, following the line.
TEST(Allocation, QuickBotFactoryStepAllocatesNothing) {
  const WindowResult r = count_step_allocations("factory_delivery.yaml", {});
  EXPECT_EQ(r.allocations, 0);
}

// Hard switching chatters (hundreds of transitions): logging them must not allocate either.
TEST(Allocation, TransitionsAreLoggedWithoutAllocating) {
  const WindowResult r =
      count_step_allocations("factory_delivery.yaml", {"controller.kind=hard_switch"});
  EXPECT_GT(r.switches, 0) << "the window should see mode switches";
  EXPECT_EQ(r.allocations, 0);
}

// A 360-beam lidar (TurtleBot3 Burger: 0.22 m/s, radius 0.105 m; dt 0.01 s keeps v dt well under
// half the radius) going round the rectangle.
TEST(Allocation, LidarRobotStepAllocatesNothing) {
  const WindowResult r = count_step_allocations(
      "rectangle.yaml", {"robot.preset=turtlebot3_burger", "sim.dt=0.01", "sim.t_max=120"});
  EXPECT_EQ(r.allocations, 0);
}

// The same lidar on an occupancy grid (a MovingAI map, 1 m cells): its beams go through
// OccupancyGrid::cast_fan.
TEST(Allocation, GridLidarRobotStepAllocatesNothing) {
  const WindowResult r = count_step_allocations(
      "movingai_template.yaml", {"goal=[29.5, 29.5]", "sim.dt=0.01", "sim.t_max=600"});
  EXPECT_EQ(r.allocations, 0);
}

// A fleet step (sensing each other, the neighbour grid, contacts) allocates nothing either.
TEST(Allocation, FleetStepAllocatesNothing) {
  Scenario s = load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/fleet_aisles.yaml");
  s.sim.record_trajectory = false;
  FleetSimulation fleet = make_fleet_simulation(s);
  for (int i = 0; i < kWarmUpSteps; ++i) EXPECT_TRUE(fleet.step());
  long allocations = 0;
  bool running = true;
  {
    const AllocationWindow window;
    for (int i = 0; i < kCountedSteps; ++i) running = fleet.step() && running;
    allocations = window.count();
  }
  EXPECT_TRUE(running) << "the fleet ended inside the counted window";
  EXPECT_EQ(allocations, 0);
}

}  // namespace
}  // namespace floornav
