// The OMPL half of the rrt_connect planner: a module (libfloornav_rrt_connect.so, the CMake
// target floornav_rrt_connect) that links libompl and is loaded on the first plan that needs a
// search (rrt_connect_loader.cpp), so that a program that never plans with rrt_connect never
// loads OMPL, Boost and ODE. It exports two C functions and nothing else.
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <type_traits>
#include <utility>
#include <vector>

#include <ompl/base/MotionValidator.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/datastructures/NearestNeighborsSqrtApprox.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include "floornav/nav/sampling_planner.hpp"
#include "floornav/planning/line_of_sight.hpp"

namespace floornav {

namespace {
namespace ob = ompl::base;
namespace og = ompl::geometric;

// OMPL's seeds are 32 bits; fold the 64-bit run seed, and keep the sampler's and the planner's
// streams apart.
std::uint_fast32_t fold(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL * (stream + 1);  // splitmix64
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return static_cast<std::uint_fast32_t>((z ^ (z >> 31)) & 0xffffffffULL);
}

// A uniform sampler of the box whose RNG is seeded by us, not by OMPL's global seed generator.
class SeededSampler final : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, std::uint_fast32_t seed)
      : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

// RRT-Connect with its own RNG seeded by us.
class SeededRrtConnect final : public og::RRTConnect {
 public:
  SeededRrtConnect(const ob::SpaceInformationPtr& si, std::uint_fast32_t seed)
      : og::RRTConnect(si) {
    rng_.setLocalSeed(seed);
  }
};

Vec2 xy(const ob::State* s) {
  const auto* v = s->as<ob::RealVectorStateSpace::StateType>();
  return {v->values[0], v->values[1]};
}

// A motion is valid when the raster's line of sight holds (exact on the cells, no resolution).
class RasterMotionValidator final : public ob::MotionValidator {
 public:
  RasterMotionValidator(const ob::SpaceInformationPtr& si, const FreeRaster& raster)
      : ob::MotionValidator(si), raster_(raster) {}
  bool checkMotion(const ob::State* a, const ob::State* b) const override {
    const bool ok = line_of_sight(raster_, xy(a), xy(b));
    if (!ok)
      ++invalid_;
    else
      ++valid_;
    return ok;
  }
  bool checkMotion(const ob::State* a, const ob::State* b,
                   std::pair<ob::State*, double>& last_valid) const override {
    if (checkMotion(a, b)) return true;
    // RRT-Connect does not ask for the last valid state; the start is always a safe answer.
    if (last_valid.first) si_->copyState(last_valid.first, a);
    last_valid.second = 0.0;
    return false;
  }

 private:
  const FreeRaster& raster_;
};

void silence_ompl() {
  static std::once_flag once;  // floornav's libraries do no I/O: OMPL's console messages go nowhere
  std::call_once(once, [] { ompl::msg::noOutputHandler(); });
}

// The search proper; rrt_connect_path (rrt_connect_loader.cpp) has checked the arguments: free
// and distinct end cells, 1 <= max_samples <= kMaxRrtConnectSamples, `out` empty.
bool search(const FreeRaster& raster, GridCell start, GridCell goal, std::uint64_t seed,
            int max_samples, std::vector<Vec2>& out) {
  silence_ompl();

  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, 0.0);
  bounds.setHigh(0, raster.width);
  bounds.setLow(1, 0.0);
  bounds.setHigh(1, raster.height);
  space->setBounds(bounds);
  std::uint64_t samplers = 0;  // a fresh, still deterministic stream for every sampler made
  space->setStateSamplerAllocator([seed, &samplers](const ob::StateSpace* s) {
    return std::make_shared<SeededSampler>(s, fold(seed, 2 + samplers++));
  });

  auto si = std::make_shared<ob::SpaceInformation>(space);
  si->setStateValidityChecker([&raster](const ob::State* s) {
    const Vec2 p = xy(s);
    return raster.is_free(static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y())));
  });
  si->setMotionValidator(std::make_shared<RasterMotionValidator>(si, raster));
  si->setup();

  ob::ScopedState<ob::RealVectorStateSpace> from(space), to(space);
  from[0] = start.x + 0.5;
  from[1] = start.y + 0.5;
  to[0] = goal.x + 0.5;
  to[1] = goal.y + 0.5;
  auto pdef = std::make_shared<ob::ProblemDefinition>(si);
  pdef->setStartAndGoalStates(from, to, 1e-9);

  SeededRrtConnect planner(si, fold(seed, 1));
  planner.setNearestNeighbors<ompl::NearestNeighborsSqrtApprox>();
  planner.setProblemDefinition(pdef);
  planner.setup();
  int iterations = 0;
  const ob::PlannerTerminationCondition budget([&] { return ++iterations > max_samples; });
  const ob::PlannerStatus status = planner.solve(budget);
  if (status != ob::PlannerStatus::EXACT_SOLUTION) return false;
  const auto* path = pdef->getSolutionPath()->as<og::PathGeometric>();
  out.reserve(path->getStateCount());
  for (std::size_t i = 0; i < path->getStateCount(); ++i) out.push_back(xy(path->getState(i)));
  return out.size() >= 2;
}

}  // namespace
}  // namespace floornav

// What the loader looks up (dlsym). The ABI tag is the version and commit both halves were
// built from: a module of another build is refused rather than called with other layouts.
extern "C" {
__attribute__((visibility("default"))) const char* floornav_rrt_connect_abi() {
  return FLOORNAV_RRT_CONNECT_ABI;
}
__attribute__((visibility("default"))) bool floornav_rrt_connect_search(
    const floornav::FreeRaster& raster, floornav::GridCell start, floornav::GridCell goal,
    std::uint64_t seed, int max_samples, std::vector<floornav::Vec2>& out) {
  return floornav::search(raster, start, goal, seed, max_samples, out);
}
}

// The loader calls it as the core's hook type: the two must not drift apart.
static_assert(std::is_same_v<decltype(&floornav_rrt_connect_search), floornav::SampledPathSearch>);
