#pragma once
/// @file
/// The checks a scenario must pass before it runs, next to the data they check: a sane step and
/// limits, sensors, controller parameters that keep the guards of Fig 5.11 ordered, starts and
/// goals in free space, robots that do not start touching.

#include <string>

#include "floornav/core/input_error.hpp"
#include "floornav/scenario/scenario.hpp"

namespace floornav {

/// The most steps (t_max / dt) a run may take.
inline constexpr double kMaxSteps = 1e8;

/// Throws InputError naming `file` and the key at fault, as the file spells it: `robot.start`,
/// `goal` and `controller.d_o` for a lone robot; `robots[2].start`, `robots[2].goal` and
/// `controller.d_o (robots[2])` for a robots list.
void validate_scenario(const Scenario& s, const std::string& file);

}  // namespace floornav
