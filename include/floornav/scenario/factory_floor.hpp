#pragma once
/// @file
/// Generated factory floors and warehouses, built in code from a seed: what `floornav batch
/// --floors N` runs, what `floornav bench` and the Google Benchmark binary time (the same work on
/// every machine), and what Python's `floornav.factory_floor` hands a learning loop.

#include <cstdint>
#include <memory>

#include "floornav/scenario/scenario.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// A walled square floor [0, side]^2 strewn with random star-shaped (simple, often concave)
/// polygons whose circumscribed discs keep `gap` metres apart, so that every robot of the
/// presets fits between them.
struct FactoryFloorParams {
  int polygons{50};              ///< obstacles
  int total_edges{0};            ///< polygon edges in all; 0: 3-8 per polygon at random
  double side{20.0};             ///< m, floor side (a 20 x 20 m hall for 50 obstacles)
  double min_radius{0.3};        ///< m, smallest circumscribed radius
  double max_radius{0.9};        ///< m, largest circumscribed radius
  double gap{0.6};               ///< m, free space between neighbouring discs
  std::uint64_t seed{20261123};  ///< the benchmarks' floor: the same on every machine
};

/// The floor described by `p`. Throws std::runtime_error when the polygons do not fit.
WorldDesc make_factory_floor(const FactoryFloorParams& p);

/// A floor with `edges` polygon edges in all (8 per polygon, as far as that goes), at the same
/// obstacle density as the 50-polygon floor: the side grows with the square root of the count.
FactoryFloorParams factory_floor_with_edges(int edges);

/// Robot `index` on `world` (a floor from make_factory_floor): a free start and a tour of four
/// free goals across the floor, drawn from a generator seeded with `index`. The robot is the
/// TurtleBot3 Burger base with a `beams`-beam 360-degree lidar (0.12-3.5 m), or the QuickBot with
/// its 5 IR sensors when `beams` is 0. Trajectory recording is off; t_max is 1e5 s.
Scenario make_factory_floor_scenario(std::shared_ptr<const World> world, int beams, int index = 0);

/// `base` (a template: robot, controller, sim) on the 50-polygon factory floor drawn from `seed`,
/// every robot starting and touring as make_factory_floor_scenario draws for that seed; named
/// "<base name>-floor<seed>". The case `floornav batch --floors` runs for `seed`. Throws
/// InputError (naming `source` and the floor) when the template's robot does not fit the floor.
Scenario make_generated_floor(const Scenario& base, std::uint64_t seed, const std::string& source);

/// A warehouse for a fleet of `robots`: a walled square hall with about 4 m^2 of floor per robot
/// (20 m across at least), racks 8 x 1 m in rows 3 m apart (2 m aisles) and 2 m cross-aisles.
WorldDesc make_fleet_warehouse(int robots);

/// `robots` robots sharing `world` (a hall from make_fleet_warehouse or make_factory_floor):
/// starts on a 0.6 m lattice of free points, drawn without repeats (so no two bodies touch),
/// headings and tours of four goals across the floor drawn from a fixed seed. QuickBots with
/// their 5 IR sensors when `beams` is 0, else the TurtleBot3 Burger base with a `beams`-beam
/// 360-degree lidar (3.5 m). Trajectory recording is off; t_max is 1e5 s.
Scenario make_fleet_scenario(std::shared_ptr<const World> world, int robots, int beams);

}  // namespace floornav
