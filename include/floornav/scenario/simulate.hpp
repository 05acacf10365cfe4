#pragma once
/// @file
/// Running a scenario: its lone robot (Simulation) or its fleet (FleetSimulation).

#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"
#include "floornav/sim/simulation.hpp"

namespace floornav {

/// A simulation of the scenario's first robot alone in its world, the run named after the
/// scenario. The scenario must outlive it. Throws std::invalid_argument for a scenario with
/// people or forklifts (Scenario::is_fleet(): only a fleet simulation moves them).
Simulation make_simulation(const Scenario& scenario);

/// A simulation of all the scenario's robots together, the run named after the scenario. The
/// scenario must outlive it.
FleetSimulation make_fleet_simulation(const Scenario& scenario);

/// Runs the scenario's first robot to the end (the whole run of a lone-robot scenario).
RunResult simulate(const Scenario& scenario);

/// Runs every robot of the scenario together to the end on `threads` threads (0: all cores).
FleetResult simulate_fleet(const Scenario& scenario, int threads = 1);

}  // namespace floornav
