#pragma once
/// @file
/// floornav::core, everything that does no I/O: the geometry and the obstacle world, the
/// differential-drive kinematics (eqs. 5.5-5.11), range sensing, robots and their presets, the
/// behaviours of sections 5.3-5.4 and the navigation automata (Fig 5.11), the controller
/// interface a user implements (nav/controller.hpp), the generic hybrid automaton engine
/// (automaton/hybrid_automaton.hpp), the simulator (one robot or a fleet) and the scenario model.
/// A scenario built in code runs with `simulate(scenario)`; reading one from a file is floornav::io
/// (floornav/io.hpp).

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/segment.hpp"
#include "floornav/geometry/vec2.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/kinematics/unicycle.hpp"
#include "floornav/nav/automaton_controller.hpp"
#include "floornav/nav/behaviours.hpp"
#include "floornav/nav/controller.hpp"
#include "floornav/nav/heading_tracker.hpp"
#include "floornav/nav/navigation_automaton.hpp"
#include "floornav/nav/navigation_controller.hpp"
#include "floornav/nav/navigation_input.hpp"
#include "floornav/nav/navigation_params.hpp"
#include "floornav/nav/pid.hpp"
#include "floornav/nav/supervisor_guards.hpp"
#include "floornav/robot/body_clearance.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/scenario.hpp"
#include "floornav/scenario/simulate.hpp"
#include "floornav/scenario/validate.hpp"
#include "floornav/sensing/obstacle_memory.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/robot_agent.hpp"
#include "floornav/sim/robot_neighbour_grid.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/sim/run_result.hpp"
#include "floornav/sim/sim_config.hpp"
#include "floornav/sim/simulation.hpp"
#include "floornav/sim/vec_simulation.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/shortest_path.hpp"
#include "floornav/world/world.hpp"
