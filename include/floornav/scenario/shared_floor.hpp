#pragma once
/// @file
/// Generated shared floors: a walled hall with pillars and boxes, a fleet of 4 to 12 robots
/// crossing it on routes of one to three goals, and on some floors people walking and a forklift
/// driving a lane. What the safety property test (tests/sim/safety_property_test.cpp) and
/// `floornav batch --shared-floors N` run: floors nobody designed, drawn from a seed.

#include <cstdint>
#include <string>

#include "floornav/scenario/scenario.hpp"

namespace floornav {

struct SharedFloorOptions {
  int min_robots{4};
  int max_robots{12};
  /// Every robot a different draw of preset (QuickBot, Khepera III, TurtleBot3, Pioneer 3-DX,
  /// Jackal), controller kind (hybrid, blended, hard_switch, go_to_goal, dwa, the A* planner
  /// stack) and cruise speed (0.5 to 1.5 times the preset's); false: QuickBots with the shipped
  /// controller, as a factory would run them.
  bool mixed{true};
  /// When given, every robot is this one (body, sensors, controller): a template's robot.
  const RobotTask* robot{nullptr};
  double people_share{0.35};   ///< share of floors with people (1 to 4 of them)
  double forklift_share{0.3};  ///< share of floors with a forklift
  double t_max{120.0};         ///< s
};

/// The floor drawn from `seed` (the same floor for the same seed and options, everywhere). The
/// scenario passes validation: starts and goals are free, apart, and out of the forklift's lane.
Scenario make_shared_floor(std::uint64_t seed, const SharedFloorOptions& options = {});

/// The shared floor drawn from `seed` with every robot `base`'s robot and controller and `base`'s
/// sim (sim.seed = `seed`), named "<base name>-shared<seed>": the case `floornav batch
/// --shared-floors` runs for `seed`. Throws InputError naming `source` and the floor when it does
/// not validate.
Scenario make_shared_floor_case(const Scenario& base, std::uint64_t seed,
                                const std::string& source);

}  // namespace floornav
