#pragma once
/// @file
/// A scenario: the world, the robots (each with its body, start, route and controller), and how
/// the simulation runs. Built by the io layer from a YAML file, or directly in code. A lone robot
/// is a fleet of one: `robots` always holds every robot.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "floornav/sim/crowd.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/sim/sim_config.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// Where a world's map came from, so that the resolved configuration of a run can name the file
/// again rather than list its cells. The io layer fills it in; a world built in code has none.
struct WorldMapSource {
  std::string path;         ///< the map file (absolute)
  double cell_size{0.0};    ///< world.cell_size, m per cell, when the format takes one (0: none)
  std::string unknown;      ///< world.unknown as given ("occupied", "free"; "" when not given)
  std::size_t circles{0};   ///< how many of the world's circles the map added (the last ones)
  std::size_t polygons{0};  ///< how many of its polygons the map added (the last ones)
};

struct Scenario {
  std::string name{"scenario"};
  std::shared_ptr<const World> world;  ///< shared by copies of the scenario (immutable)
  std::vector<RobotTask> robots;       ///< at least one
  SimConfig sim{};
  /// The robots came as a `robots:` list (a fleet, even of one): outputs are per robot (a robot
  /// column, every robot's summary) and errors name `robots[i]`. False for a `robot:` section.
  bool robots_listed{false};
  /// People and forklifts moving on the floor (`people:`, `people_file:`, `forklifts:`).
  CrowdSpec crowd{};
  /// The file behind `world`'s map, if it has one (see WorldMapSource).
  std::optional<WorldMapSource> world_map;
  /// Every file the io layer read to make the scenario, in the order read: the scenario file, its
  /// map (and a map yaml's image), its people_file. A sweep's id fingerprints their content, so
  /// that a folder of results is resumed or merged only with the very inputs it was made from.
  /// Empty for a scenario built in code.
  std::vector<std::string> input_files;

  /// Outputs and runs as a fleet (FleetSimulation) rather than a lone robot (Simulation): also
  /// a lone robot among people or forklifts (only a fleet simulates them).
  bool is_fleet() const { return robots_listed || robots.size() != 1 || !crowd.empty(); }
  /// The first (for a lone-robot scenario, the only) robot.
  const RobotTask& robot() const { return robots.front(); }
  RobotTask& robot() { return robots.front(); }

  /// Every robot drives with the controller that `factory` makes, reported as `kind`.
  void set_controller(std::string kind, ControllerFactory factory);
};

}  // namespace floornav
