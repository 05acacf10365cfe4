// "Slower must never be less safe" (issue 33) attacked with draws rather than a grid: the
// chapter's scenes at cruise speeds drawn from [0.05, 0.3] m/s (the QuickBot's top speed is
// 0.44), as written and then from starts and controller kinds nobody tuned them on. The safety
// layer is on, as shipped: whatever is drawn, the robot never touches anything.
//
// FLOORNAV_CHAPTER_DRAWS=N draws N cases per test instead of the suite's bounded count.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"
#include "support/property_count.hpp"

using namespace floornav;

namespace {

constexpr std::array<const char*, 9> kScenes{
    "point_obstacle.yaml",    "circle_obstacle.yaml",  "rectangle.yaml",
    "convex_obstacle.yaml",   "concave_obstacle.yaml", "week7_pocket.yaml",
    "practice2_pillars.yaml", "factory_delivery.yaml", "coppeliasim_pioneer.yaml"};

int draws(int default_count) {
  return test::property_count("FLOORNAV_CHAPTER_DRAWS", default_count);
}

std::string path(const char* scene) {
  return std::string(FLOORNAV_SCENARIO_DIR) + "/" + scene;
}

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", x);
  return text;
}

// A drawn case: the scene with its overrides, loaded (and validated) as `floornav run --set`
// would load it.
struct Case {
  std::string scene;
  std::vector<std::string> sets;
  std::string describe() const {
    std::string d = scene;
    for (const std::string& s : sets) d += " --set " + s;
    return d;
  }
};

// Each scene as written, loaded once.
const Scenario& as_written(std::size_t scene) {
  static const std::vector<Scenario> scenes = [] {
    std::vector<Scenario> all;
    for (const char* s : kScenes) all.push_back(load_scenario_file(path(s)));
    return all;
  }();
  return scenes[scene];
}

// The scene's time limit, stretched for a drawn speed below the one it was written for: a
// scene timed for 0.3 m/s gets six times as long at 0.05 m/s (a livelock still runs out of it).
double slowed_time_limit(std::size_t scene, double v0) {
  const Scenario& s = as_written(scene);
  return s.sim.t_max * std::max(1.0, s.robots.front().controller.params.v0 / v0);
}

void expect_never_touches(const Case& c, const RunResult& r) {
  EXPECT_FALSE(r.collided) << c.describe();
  EXPECT_GT(r.min_clearance, 0.0) << c.describe();
}

}  // namespace

// The scenes as written (their own controller, start and goal) at drawn speeds: never a
// contact, and at least 90 % reached within the scene's time limit stretched for the speed (the
// issue's target; the blended controller stops in its own local minima, the chapter's point
// about blending).
TEST(ChapterSpeedProperty, ScenesAsWrittenAtDrawnSpeedsNeverTouch) {
  Rng rng(20261207);
  const int n = draws(450);
  int reached = 0;
  std::map<std::string, int> missed;
  for (int k = 0; k < n; ++k) {
    const std::size_t scene = static_cast<std::size_t>(k) % kScenes.size();
    Case c{kScenes[scene], {}};
    const double v0 = rng.uniform(0.05, 0.3);
    c.sets.push_back("controller.v0=" + number(v0));
    c.sets.push_back("sim.t_max=" + number(slowed_time_limit(scene, v0)));
    const RunResult r = simulate(load_scenario_file(path(c.scene.c_str()), c.sets));
    expect_never_touches(c, r);
    reached += r.status == RunStatus::Reached;
    if (r.status != RunStatus::Reached) ++missed[c.scene + " " + std::string(to_string(r.status))];
  }
  std::printf("chapter scenes at drawn speeds: %d of %d reached\n", reached, n);
  for (const auto& [what, count] : missed) std::printf("  %d %s\n", count, what.c_str());
  EXPECT_GE(10 * reached, 9 * n);
}

// Any of the chapter's controllers, from a drawn start (within 0.2 m of the scene's, any
// heading) at a drawn speed: never a contact. Starts that would touch are drawn again (the
// loader refuses them).
TEST(ChapterSpeedProperty, AnyControllerFromDrawnStartsNeverTouches) {
  constexpr std::array<const char*, 4> kKinds{"hybrid", "blended", "hard_switch", "go_to_goal"};
  Rng rng(7);
  const int n = draws(450);
  int reached = 0, refused = 0;
  for (int k = 0; k < n; ++k) {
    const std::size_t index = static_cast<std::size_t>(k) % kScenes.size();
    const char* scene = kScenes[index];
    const Pose2 start = as_written(index).robots.front().start;
    bool ran = false;
    for (int attempt = 0; attempt < 50 && !ran; ++attempt) {
      const Vec2 at = start.position + Vec2(rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2));
      Case c{scene,
             {"controller.kind=" + std::string(kKinds[rng.next() % kKinds.size()]),
              "controller.v0=" + number(rng.uniform(0.05, 0.3)),
              "robot.start=[" + number(at.x()) + "," + number(at.y()) + "," +
                  number(rng.uniform(-kPi, kPi)) + "]"}};
      Scenario s;
      try {
        s = load_scenario_file(path(scene), c.sets);
      } catch (const std::exception&) {
        ++refused;  // the drawn start touches something: draw again
        continue;
      }
      const RunResult r = simulate(s);
      expect_never_touches(c, r);
      reached += r.status == RunStatus::Reached;
      ran = true;
    }
    ASSERT_TRUE(ran) << scene << ": 50 drawn starts refused";
  }
  std::printf("drawn controllers, starts and speeds: %d of %d reached (%d starts refused)\n",
              reached, n, refused);
}
