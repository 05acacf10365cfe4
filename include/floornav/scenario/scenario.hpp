#pragma once
/// @file
/// A scenario: the world, the robot, where it starts, where it must go, how it decides, and how
/// the simulation runs. Built by the io layer from a YAML file, or directly in code.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "floornav/geometry/pose2.hpp"
#include "floornav/nav/navigation_params.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// How a run is simulated.
struct SimConfig {
  double dt{0.01};               ///< s, fixed control and integration step
  double t_max{120.0};           ///< s, then the run ends as `timeout`
  std::uint64_t seed{1};         ///< the run's random seed (sensor noise)
  double stuck_window{10.0};     ///< s: a robot that stays within stuck_radius this long is `stuck`
  double stuck_radius{0.0};      ///< m; 0 means the robot's body radius
  bool record_trajectory{true};  ///< keep every step (for CSV and SVG); off in big batches
  bool park_finished{true};      ///< fleets: a robot that is done stays, an obstacle to others

  template <class Archive>
  void serialize(Archive& a) {
    a("dt", dt, "fixed time step, s");
    a("t_max", t_max, "simulated time limit, s");
    a("seed", seed, "random seed (sensor noise)");
    a("stuck_window", stuck_window, "a robot that stays within stuck_radius this long is stuck, s");
    a("stuck_radius", stuck_radius, "m; 0 means the body radius");
    a("record_trajectory", record_trajectory, "keep every step for the CSV and SVG outputs");
    a("park_finished", park_finished,
      "fleets: a robot that has finished stays where it stopped, an obstacle to the others");
  }
};

/// One robot of a fleet: its own body, start, delivery route and controller.
struct RobotTask {
  std::string name;
  RobotSpec robot{};
  Pose2 start{};
  std::vector<Vec2> goals;  ///< visited in order
  ControllerKind controller{ControllerKind::Hybrid};
  NavigationParams navigation{};
};

struct Scenario {
  std::string name{"scenario"};
  std::shared_ptr<const OccupancyGrid> grid;  ///< keeps the world's map alive, if it has one
  std::shared_ptr<const World> world;
  RobotSpec robot{};
  Pose2 start{};
  std::vector<Vec2> goals;  ///< visited in order
  ControllerKind controller{ControllerKind::Hybrid};
  NavigationParams navigation{};
  SimConfig sim{};
  /// A fleet sharing the world (FleetSimulation). Empty: the one robot above. When it is set,
  /// robot, start, goals, controller and navigation repeat robots[0], so that code asking
  /// about "the robot" (validation, pictures) gets a sensible answer.
  std::vector<RobotTask> robots;
};

/// Makes robot, start, goals, controller and navigation repeat robots[0] (see Scenario::robots).
inline void repeat_first_robot(Scenario& s) {
  if (s.robots.empty()) return;
  const RobotTask& first = s.robots.front();
  s.robot = first.robot;
  s.start = first.start;
  s.goals = first.goals;
  s.controller = first.controller;
  s.navigation = first.navigation;
}

}  // namespace floornav
