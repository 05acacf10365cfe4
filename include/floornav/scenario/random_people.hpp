#pragma once
/// @file
/// People at a given density (`random_people:`): walkers placed at random on the free floor of a
/// region, each on a cyclic route of random waypoints it can walk to in straight lines, drawn
/// from the scenario's seed. What a people-density sweep varies (docs/BENCHMARKS.md, "People
/// density"): the same floor and robots with 0.1 to 0.5 people per m².

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "floornav/geometry/box2.hpp"
#include "floornav/sim/crowd.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

struct RandomPeopleSpec {
  double density{0.1};         ///< people per m² of free floor in the region, (0, 2]
  std::optional<Box2> region;  ///< where they start and walk (m); none: the world's bounds
  double min_speed{0.8};       ///< m/s: each walker's speed is drawn in [min_speed, max_speed]
  double max_speed{1.3};       ///< m/s (a typical walking pace is 1.2-1.4)
  double radius{0.25};         ///< m: every walker's body disc
  int waypoints{3};            ///< waypoints per walker, walked cyclically, in [1, 1000]
};

/// What place_random_people() placed, and how many the density asked for.
struct RandomPeople {
  std::vector<PersonSpec> people;
  std::size_t asked{0};   ///< round(density * free_area)
  double free_area{0.0};  ///< m²: the free floor of the region
};

/// m²: the area of `region` that is free floor (neither inside an obstacle nor outside the
/// world), measured on a lattice of cells of at most 0.05 m (coarser beyond a million cells).
double free_floor_area(const World& world, const Box2& region);

/// The region `spec` names, else the world's bounds, else its extent.
Box2 random_people_region(const World& world, const RandomPeopleSpec& spec);

/// Walkers named walker0, walker1, ... drawn from `seed` (the same people for the same inputs,
/// everywhere). A walker starts with its body 0.1 m clear of the world, 0.1 m apart from every
/// other person (`existing` included), beyond the personal space (0.5 m) of every robot's start
/// and clear of every forklift's first footprint by 0.3 m. Each waypoint is free floor the body
/// fits on, reached from the point before it (the first from the start, and the first again
/// from the last: the route is cyclic) along a straight line the body clears, so that no walker
/// is sent into a wall. Fewer than `asked` when the floor is too full to place them all (the
/// caller reports that).
RandomPeople place_random_people(const World& world, const RandomPeopleSpec& spec,
                                 std::span<const RobotTask> robots,
                                 std::span<const PersonSpec> existing,
                                 std::span<const ForkliftSpec> forklifts, std::uint64_t seed);

}  // namespace floornav
