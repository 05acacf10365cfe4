// VecSimulation (many copies stepped together on a worker pool) and the observe/step split of
// Simulation: a copy runs exactly as a Simulation with its seed, whatever the threads; the
// sensors are cast once per step; a finished run is sensed once where it stopped.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "floornav/io/scenario_file.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/sim/simulation.hpp"
#include "floornav/sim/vec_simulation.hpp"

using namespace floornav;

namespace {

Scenario scenario_file(const std::string& name, std::vector<std::string> sets = {}) {
  return load_scenario_file(std::string(FLOORNAV_SCENARIO_DIR) + "/" + name, sets);
}

// Sensor noise on: a second sensing in a step would draw other numbers and move the robot.
Scenario noisy(std::vector<std::string> sets = {}) {
  sets.push_back("robot.sensors.noise=0.01");
  return scenario_file("rectangle.yaml", sets);
}

Command command_for(std::size_t copy, int step) {
  return Command::unicycle(0.05 + 0.02 * static_cast<double>(copy % 5),
                           0.6 * std::sin(0.05 * step + static_cast<double>(copy)));
}

std::vector<VecCopy> copies(const Scenario& s, std::size_t n) {
  return std::vector<VecCopy>(n, VecCopy{s.world.get(), &s.robot(), &s.sim, s.name});
}

}  // namespace

TEST(WorkerPool, RunsEveryIndexOnceAndRethrows) {
  WorkerPool pool(2);
  EXPECT_EQ(pool.size(), 2u);
  std::vector<std::atomic<int>> hits(1000);
  pool.run(hits.size(), 7, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) ++hits[i];
  });
  for (const auto& h : hits) EXPECT_EQ(h.load(), 1);
  EXPECT_THROW(pool.run(100, 1,
                        [](std::size_t b, std::size_t) {
                          if (b == 42) throw std::runtime_error("copy 42 failed");
                        }),
               std::runtime_error);
  // ... and stays usable
  std::atomic<int> n{0};
  pool.run(10, 1, [&](std::size_t b, std::size_t e) { n += static_cast<int>(e - b); });
  EXPECT_EQ(n.load(), 10);
}

// Workers spin a while for the next run before they sleep; an idle pool must not spin on.
TEST(WorkerPool, AnIdlePoolSleepsAfterSpinningAWhile) {
  WorkerPool pool(2);
  std::atomic<int> n{0};
  for (int k = 0; k < 100; ++k)
    pool.run(100, 10, [&](std::size_t b, std::size_t e) { n += static_cast<int>(e - b); });
  EXPECT_EQ(n.load(), 100 * 100);
  const auto cpu = [] {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
  };
  const double before = cpu();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  // The worker's spinning (about a millisecond) and nothing after it.
  EXPECT_LT(cpu() - before, 0.1);
}

// pool.run(100, 10, ...) with index `hold`, when the caller (`held_by_caller`) or else the
// worker reaches it, waiting up to 10 s for index `until` to be done. The threads that ran each
// index, in the order they were run.
std::vector<std::pair<std::size_t, std::thread::id>> run_holding(WorkerPool& pool, std::size_t hold,
                                                                 bool held_by_caller,
                                                                 std::size_t until) {
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<std::pair<std::size_t, std::thread::id>> order;
  std::vector<bool> done(100, false);
  std::mutex m;
  std::condition_variable cv;
  pool.run(done.size(), 10, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      std::unique_lock lock(m);
      const std::thread::id self = std::this_thread::get_id();
      order.emplace_back(i, self);
      if (i == hold && (self == caller) == held_by_caller)
        cv.wait_for(lock, std::chrono::seconds(10), [&] { return done[until]; });
      done[i] = true;
      cv.notify_all();
    }
  });
  return order;
}

// The first index `thread` ran, or -1.
long first_run_by(const std::vector<std::pair<std::size_t, std::thread::id>>& order,
                  std::thread::id thread) {
  for (const auto& [i, t] : order)
    if (t == thread) return static_cast<long>(i);
  return -1;
}

TEST(WorkerPool, EachThreadStartsOnItsShareAndTheIdleStealFromTheBack) {
  // Copy i goes to the same thread every step, so its data stays in that core's cache: the
  // caller starts at 0, the worker at n / 2 (the caller held at 0 until the worker ran 50).
  WorkerPool pool(2);
  const std::thread::id caller = std::this_thread::get_id();
  // Which thread logs first is the scheduler's choice (a woken worker may beat the caller): each
  // thread's first index is what is asserted.
  auto order = run_holding(pool, 0, true, 50);
  ASSERT_EQ(order.size(), 100u);
  EXPECT_EQ(first_run_by(order, caller), 0);
  const auto other = std::find_if(order.begin(), order.end(),
                                  [&](const auto& entry) { return entry.second != caller; });
  ASSERT_NE(other, order.end());
  EXPECT_EQ(first_run_by(order, other->second), 50);
  // A worker held on its first index leaves the rest of its share to the caller, who takes it
  // from the back: index 99 is the caller's (so the hold ends before its 10 s).
  order = run_holding(pool, 50, false, 99);
  ASSERT_EQ(order.size(), 100u);
  std::thread::id last;
  for (const auto& [i, t] : order)
    if (i == 99) last = t;
  EXPECT_EQ(last, caller);
  EXPECT_EQ(first_run_by(order, caller), 0);
}

TEST(Simulation, ObserveBeforeStepSharesTheStepsSensing) {
  const Scenario s = noisy();
  Simulation plain = make_simulation(s), observed = make_simulation(s);
  for (int k = 0; k < 1500; ++k) {
    for (int j = 0; j < 3; ++j) observed.observe();
    plain.step();
    observed.step();
    ASSERT_EQ(plain.pose().position, observed.pose().position) << "step " << k;
  }
  // The noise matters: another seed drives elsewhere, so a second draw would have shown.
  Scenario other = s;
  other.sim.seed = 2;
  Simulation reseeded = make_simulation(other);
  for (int k = 0; k < 1500; ++k) reseeded.step();
  EXPECT_NE(reseeded.pose().position, plain.pose().position);
}

TEST(Simulation, AFinishedRunIsObservedWhereItStopped) {
  // Straight into the rectangle's face at x = 1.0: the last observation is sensed at the
  // final pose (the front IR sensor sits 0.0664 m ahead of the centre, min range 0.04 m).
  const Scenario s =
      scenario_file("rectangle.yaml", {"robot.start=[0.85, 0, 0]", "controller.safety=off"});
  Simulation sim = make_simulation(s);
  while (sim.step(Command::unicycle(0.2, 0.0))) {
  }
  ASSERT_EQ(sim.result().status, RunStatus::Collision);
  const Observation obs = sim.observe();
  EXPECT_EQ(obs.pose.position, sim.pose().position);
  EXPECT_NEAR(obs.ranges[2], std::max(0.04, 1.0 - (sim.pose().position.x() + 0.0664)), 1e-9);
  EXPECT_EQ(sim.observe().ranges[2], obs.ranges[2]);  // sensed once
}

TEST(VecSimulation, EachCopyEqualsASimulationWithItsSeed) {
  const Scenario s = noisy();
  constexpr std::size_t kCopies = 6;
  VecSimulation vec(copies(s, kCopies), 2);
  EXPECT_EQ(vec.size(), kCopies);
  EXPECT_EQ(vec.beam_count(), 5u);
  std::vector<Scenario> seeded(kCopies, s);
  std::vector<Simulation> sims;
  for (std::size_t i = 0; i < kCopies; ++i) {
    vec.reset(i, 100 + i);
    seeded[i].sim.seed = 100 + i;
  }
  for (std::size_t i = 0; i < kCopies; ++i) sims.push_back(make_simulation(seeded[i]));
  for (int k = 0; k < 800; ++k) {
    std::vector<Command> commands;
    for (std::size_t i = 0; i < kCopies; ++i) commands.push_back(command_for(i, k));
    vec.step(commands);
    for (std::size_t i = 0; i < kCopies; ++i) {
      sims[i].step(commands[i]);
      ASSERT_EQ(vec.agent(i).pose().position, sims[i].pose().position) << k << " " << i;
      ASSERT_EQ(vec.agent(i).pose().theta, sims[i].pose().theta);
      const Observation a = vec.observe(i), b = sims[i].observe();
      for (std::size_t j = 0; j < 5; ++j) ASSERT_EQ(a.ranges[j], b.ranges[j]);
    }
  }
  // A learner reads no copy's result: the path irregularity (an atan2 a step) is not summed.
  for (std::size_t i = 0; i < kCopies; ++i) {
    EXPECT_TRUE(std::isnan(vec.agent(i).result().path_irregularity)) << i;
    EXPECT_GT(sims[i].result().path_irregularity, 0.0) << i;
  }
}

// Copies of one kind (here two equal scenarios, not one) read one robot model; one with another
// body keeps its own.
TEST(VecSimulation, CopiesOfOneKindShareOneRobotModel) {
  const Scenario a = noisy(), b = noisy();
  Scenario other = noisy();
  other.robots[0].robot.body_radius += 0.01;
  std::vector<VecCopy> mixed = copies(a, 1);
  mixed.push_back(copies(b, 1).front());
  mixed.push_back(copies(other, 1).front());
  VecSimulation vec(mixed, 1);
  for (std::size_t i = 0; i < 3; ++i) vec.reset(i, i);
  EXPECT_EQ(&vec.agent(0).robot(), &vec.agent(1).robot());
  EXPECT_EQ(&vec.agent(0).params(), &vec.agent(1).params());
  EXPECT_NE(&vec.agent(0).robot(), &vec.agent(2).robot());
  EXPECT_EQ(vec.agent(2).body_radius(), other.robots[0].robot.body_radius);
}

TEST(VecSimulation, ControllersDriveWithoutCommandsAndThreadsChangeNothing) {
  const Scenario s = noisy();
  VecSimulation one(copies(s, 40), 1), two(copies(s, 40), 2);
  EXPECT_EQ(one.thread_count(), 1u);
  EXPECT_EQ(two.thread_count(), 2u);
  std::vector<std::size_t> which(40);
  std::vector<std::uint64_t> seeds(40);
  for (std::size_t i = 0; i < 40; ++i) which[i] = i, seeds[i] = i;
  one.reset(which, seeds);
  two.reset(which, seeds);
  std::vector<int> visited(40, 0);
  for (int k = 0; k < 3000; ++k) {
    one.step({});
    two.step({}, [&](std::size_t i) { ++visited[i]; });
  }
  for (std::size_t i = 0; i < 40; ++i) {
    EXPECT_EQ(visited[i], 3000);
    EXPECT_EQ(one.agent(i).pose().position, two.agent(i).pose().position);
    EXPECT_EQ(one.agent(i).result().steps, two.agent(i).result().steps);
  }
  // The controller reached the goal in some copies: they stopped and stayed put.
  int reached = 0;
  for (std::size_t i = 0; i < 40; ++i)
    reached += one.agent(i).finished() && one.agent(i).result().status == RunStatus::Reached;
  EXPECT_GT(reached, 0);
  // A copy alone with its seed runs the same.
  Scenario s7 = s;
  s7.sim.seed = 7;
  Simulation sim = make_simulation(s7);
  for (int k = 0; k < 3000; ++k) sim.step();
  EXPECT_EQ(sim.pose().position, one.agent(7).pose().position);
}

TEST(VecSimulation, RefusesBadSetUpsAndBadCommands) {
  const Scenario s = noisy();
  const Scenario pioneer = scenario_file("coppeliasim_pioneer.yaml");
  std::vector<VecCopy> mixed = copies(s, 1);
  mixed.push_back({pioneer.world.get(), &pioneer.robot(), &pioneer.sim, "pioneer"});
  EXPECT_THROW(VecSimulation(mixed, 1), std::invalid_argument);  // other sensor count
  EXPECT_THROW(VecSimulation({}, 1), std::invalid_argument);
  VecSimulation vec(copies(s, 3), 2);
  EXPECT_THROW(vec.step({}), std::logic_error);  // not reset yet
  for (std::size_t i = 0; i < 3; ++i) vec.reset(i, i);
  std::vector<Command> two(2, Command::unicycle(0.1, 0.0));
  EXPECT_THROW(vec.step(two), std::invalid_argument);
  std::vector<Command> bad(3, Command::unicycle(0.1, 0.0));
  bad[1] = Command::unicycle(std::nan(""), 0.0);
  EXPECT_THROW(vec.step(bad), std::domain_error);
}

// A copy source gives each episode a world of its own: a reset takes the copy it returns (its
// world, start and seed), the episode runs as a Simulation of that scenario, and the next reset
// asks again; a source that changes the robot is refused.
TEST(VecSimulation, ACopySourceGivesEachEpisodeItsOwnCopy) {
  const Scenario s = noisy();
  const Scenario other = scenario_file("point_obstacle.yaml", {"robot.sensors.noise=0.01"});
  ASSERT_EQ(other.robot().robot, s.robot().robot);
  ASSERT_EQ(other.robot().controller.params, s.robot().controller.params);
  VecSimulation vec(copies(s, 2), 1);
  std::vector<std::pair<std::size_t, std::uint64_t>> asked;
  vec.set_copy_source([&](std::size_t i, std::uint64_t seed) {
    asked.emplace_back(i, seed);
    const Scenario& x = seed % 2 ? other : s;
    return VecCopy{x.world.get(), &x.robot(), &x.sim, x.name};
  });
  vec.reset(0, 7);  // odd: the other scenario
  vec.reset(1, 8);
  EXPECT_EQ(vec.copy(0).world, other.world.get());
  EXPECT_EQ(vec.copy(1).world, s.world.get());
  EXPECT_EQ(vec.task(0).start.position, other.robot().start.position);
  Scenario seeded = other;
  seeded.sim.seed = 7;
  Simulation alone = make_simulation(seeded);
  for (int k = 0; k < 300; ++k) {
    const Command c = command_for(0, k);
    vec.step(std::vector<Command>{c, c});
    alone.step(c);
    ASSERT_EQ(vec.agent(0).pose().position, alone.pose().position) << k;
  }
  vec.reset(0, 10);  // the next episode: asked again, on the first scenario
  EXPECT_EQ(vec.copy(0).world, s.world.get());
  EXPECT_EQ(asked, (std::vector<std::pair<std::size_t, std::uint64_t>>{{0, 7}, {1, 8}, {0, 10}}));

  const Scenario pioneer = scenario_file("coppeliasim_pioneer.yaml");
  vec.set_copy_source([&](std::size_t, std::uint64_t) {
    return VecCopy{pioneer.world.get(), &pioneer.robot(), &pioneer.sim, "pioneer"};
  });
  EXPECT_THROW(vec.reset(1, 3), std::invalid_argument);
}

namespace {

// 24 QuickBots with a noisy 72-beam lidar (cast as a fan) among pillars, from one start: some
// reach the goal within t_max and end while the others run.
Scenario lidar_floor() {
  return load_scenario_text(
      "world: {bounds: [0, 0, 6, 4], obstacles: [{circle: {center: [3, 2], radius: 0.4}}, "
      "{polygon: [[1.5, 0.6], [2.0, 0.6], [2.0, 1.1]]}]}\n"
      "robot: {preset: quickbot, start: [0.5, 2, 0], sensors: {noise: 0.003, lidar: {beams: 72, "
      "fov: 6.283185307, min_range: 0.02, max_range: 1.5}}}\n"
      "goal: [1.8, 2.6]\n"
      "sim: {t_max: 25}\n",
      "lidar_floor.yaml");
}

struct SeenFrame {
  std::vector<double> ranges;
  std::vector<SensorBeam> beams;
};

void expect_same_frame(const Observation& o, const SeenFrame& seen, const std::string& where) {
  ASSERT_EQ(o.ranges.size(), seen.ranges.size()) << where;
  for (std::size_t j = 0; j < seen.ranges.size(); ++j) {
    ASSERT_EQ(o.ranges[j], seen.ranges[j]) << where << " beam " << j;
    ASSERT_EQ(o.beams[j].origin, seen.beams[j].origin) << where;
    ASSERT_EQ(o.beams[j].dir, seen.beams[j].dir) << where;
    ASSERT_EQ(o.beams[j].theta, seen.beams[j].theta) << where;
  }
}

}  // namespace

// keep_frames(false): copies whose controllers read no frame sense into their thread's, and
// after(i) sees every observation exactly as with kept frames; elsewhere a running copy shows
// none and holds none, and a copy that has ended keeps its last one.
TEST(VecSimulation, WithoutKeptFramesEachObservationIsTheSameInsideAfter) {
  const Scenario s = lidar_floor();
  ASSERT_FALSE(controller_reads_frames(s.robot().controller));
  constexpr std::size_t kCopies = 24;
  VecSimulation kept(copies(s, kCopies), 2), lean(copies(s, kCopies), 2);
  lean.keep_frames(false);
  std::vector<std::size_t> which(kCopies);
  std::vector<std::uint64_t> seeds(kCopies);
  for (std::size_t i = 0; i < kCopies; ++i) which[i] = i, seeds[i] = 50 + i;
  std::vector<SeenFrame> seen(kCopies);
  const auto record = [&](std::size_t i) {
    const Observation o = lean.observe(i);
    seen[i].ranges.assign(o.ranges.begin(), o.ranges.end());
    seen[i].beams.assign(o.beams.begin(), o.beams.end());
  };
  kept.reset(which, seeds);
  lean.reset(which, seeds, record);
  std::size_t ended_checked = 0;
  for (int k = 0; k <= 2500; ++k) {
    for (std::size_t i = 0; i < kCopies; ++i) {
      const std::string where = "step " + std::to_string(k) + " copy " + std::to_string(i);
      ASSERT_EQ(lean.agent(i).pose().position, kept.agent(i).pose().position) << where;
      ASSERT_EQ(seen[i].ranges.size(), 72u) << where;
      expect_same_frame(kept.observe(i), seen[i], where);
      const Observation outside = lean.observe(i);
      if (lean.agent(i).finished()) {
        expect_same_frame(outside, seen[i], where);
        ++ended_checked;
      } else {
        EXPECT_TRUE(outside.ranges.empty() && outside.beams.empty()) << where;
        EXPECT_TRUE(lean.sensing(i).frame.beams.empty()) << where;
      }
      ASSERT_EQ(outside.sensed.size(), kept.observe(i).sensed.size()) << where;
    }
    // Commands first, then the controllers drive (reading the returns each copy kept).
    std::vector<Command> commands;
    if (k < 600)
      for (std::size_t i = 0; i < kCopies; ++i) commands.push_back(command_for(i, k));
    kept.step(commands);
    lean.step(commands, record);
  }
  EXPECT_GT(ended_checked, 0u) << "no copy ended";  // some reached the goal
}

// A user's controller (and the planning layer) may read the beams and ranges: such copies keep
// theirs, and steer by them as with kept frames.
TEST(VecSimulation, CopiesWhoseControllersReadFramesKeepThem) {
  Scenario s = lidar_floor();
  ControllerConfig planned = s.robot().controller;
  planned.planner.kind = PlannerKind::AStar;
  EXPECT_TRUE(controller_reads_frames(planned));
  // Turns towards the side with more room, by the ranges at +-45 degrees.
  s.robots[0].controller.factory = make_controller([](const Observation& obs) {
    if (obs.ranges.size() != 72) throw std::logic_error("no frame to steer by");
    return Command::unicycle(0.08, 2.0 * (obs.ranges[9] - obs.ranges[63]));
  });
  ASSERT_TRUE(controller_reads_frames(s.robot().controller));
  constexpr std::size_t kCopies = 8;
  VecSimulation kept(copies(s, kCopies), 2), lean(copies(s, kCopies), 2);
  lean.keep_frames(false);
  for (std::size_t i = 0; i < kCopies; ++i) {
    kept.reset(i, i);
    lean.reset(i, i);
  }
  for (int k = 0; k < 400; ++k) {
    kept.step({});
    lean.step({});
  }
  for (std::size_t i = 0; i < kCopies; ++i) {
    EXPECT_EQ(lean.agent(i).pose().position, kept.agent(i).pose().position) << i;
    EXPECT_EQ(lean.observe(i).ranges.size(), 72u) << i;
  }
}
