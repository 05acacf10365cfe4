// "Same scenario and seed: the same trajectory, bit for bit, on any number of threads", attacked
// with floors nobody designed: generated shared floors (scenario/shared_floor.hpp) of mixed
// presets, controller kinds and speeds, recorded, each run on one thread and on two. Every
// trajectory row of every robot, every person's and forklift's, and the summary must match bit
// for bit. Only floors with work enough to be split across two threads (lidar robots:
// TurtleBot3s, Jackals) are run: the others run on one thread either way. Every other floor has
// people and a forklift.
//
// FLOORNAV_THREAD_FLOORS=N runs N floors instead of the suite's bounded count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>

#include "floornav/io/summary_json.hpp"
#include "floornav/scenario/shared_floor.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "support/bits.hpp"
#include "support/property_count.hpp"

using namespace floornav;

namespace {

// Bit for bit: every double compared as its bits, so that a NaN or a signed zero cannot hide
// (a row's padding is not compared).
bool same_bits(double a, double b) {
  return test::bits(a) == test::bits(b);
}
bool same_bits(const TrajectorySample& a, const TrajectorySample& b) {
  return same_bits(a.t, b.t) && same_bits(a.x, b.x) && same_bits(a.y, b.y) &&
         same_bits(a.theta, b.theta) && same_bits(a.v, b.v) && same_bits(a.omega, b.omega) &&
         same_bits(a.w_left, b.w_left) && same_bits(a.w_right, b.w_right) && a.mode == b.mode;
}
bool same_bits(const CrowdSample& a, const CrowdSample& b) {
  return same_bits(a.t, b.t) && same_bits(a.x, b.x) && same_bits(a.y, b.y) &&
         same_bits(a.theta, b.theta);
}
template <class Row>
bool same_bits(const std::vector<Row>& a, const std::vector<Row>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [](const Row& x, const Row& y) { return same_bits(x, y); });
}

// The first robot (or -1) whose trajectory differs, for the failure message.
int first_differing_robot(const FleetResult& a, const FleetResult& b) {
  for (std::size_t i = 0; i < a.robots.size(); ++i)
    if (!same_bits(a.robots[i].trajectory, b.robots[i].trajectory)) return static_cast<int>(i);
  return -1;
}

}  // namespace

TEST(ThreadProperty, GeneratedFloorsGiveTheSameBitsOnOneThreadAndTwo) {
  const int n = test::property_count("FLOORNAV_THREAD_FLOORS", 8);
  int ran = 0, drawn = 0, rows = 0, people = 0, forklifts = 0;
  for (std::uint64_t seed = 3000; ran < n && drawn < 50 * n; ++seed, ++drawn) {
    // Every other floor among people and a forklift (the first one too, so that a single floor,
    // the count of a build without NDEBUG, has them), the others with robots alone.
    const bool crowded = ran % 2 == 0;
    SharedFloorOptions o;
    o.min_robots = 8;
    o.t_max = 15.0;
    o.people_share = crowded ? 1.0 : 0.0;
    o.forklift_share = crowded ? 1.0 : 0.0;
    Scenario s = make_shared_floor(seed, o);
    if (crowded && (s.crowd.people.empty() || s.crowd.forklifts.empty())) continue;
    s.sim.record_trajectory = true;
    FleetSimulation one = make_fleet_simulation(s), two = make_fleet_simulation(s);
    // A floor of a few QuickBots is too little work to split: it runs on one thread either way
    // and would test nothing.
    if (two.threads_for(2) != 2) continue;
    ++ran;
    one.run(1);
    two.run(2);
    const FleetResult a = one.result(), b = two.result();
    ASSERT_EQ(a.robots.size(), b.robots.size()) << s.name;
    EXPECT_EQ(first_differing_robot(a, b), -1) << s.name << " (seed " << seed << ")";
    for (const RunResult& r : a.robots) rows += static_cast<int>(r.trajectory.size());
    people += static_cast<int>(a.crowd.people.size());
    forklifts += static_cast<int>(a.crowd.forklifts.size());
    ASSERT_EQ(a.crowd.people.size(), b.crowd.people.size()) << s.name;
    for (std::size_t p = 0; p < a.crowd.people.size(); ++p)
      EXPECT_TRUE(same_bits(a.crowd.people[p].samples, b.crowd.people[p].samples)) << s.name;
    ASSERT_EQ(a.crowd.forklifts.size(), b.crowd.forklifts.size()) << s.name;
    for (std::size_t f = 0; f < a.crowd.forklifts.size(); ++f)
      EXPECT_TRUE(same_bits(a.crowd.forklifts[f].samples, b.crowd.forklifts[f].samples)) << s.name;
    EXPECT_EQ(fleet_summary_to_json(a).dump(), fleet_summary_to_json(b).dump()) << s.name;
  }
  std::printf(
      "%d generated floors split across two threads (of %d drawn): %d trajectory rows, "
      "%d people, %d forklifts\n",
      ran, drawn, rows, people, forklifts);
  ASSERT_EQ(ran, n) << "the generator drew too few floors worth a second thread";
  EXPECT_GT(people, 0);
  EXPECT_GT(forklifts, 0);
}
