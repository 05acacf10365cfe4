#pragma once
/// @file
/// Private to the render module: the two lines of text over a picture of a run (SVG and HTML):
/// what ran and how it ended, then its numbers.

#include <string>

#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav::render_detail {

struct Caption {
  std::string title;    ///< "rectangle — hybrid — reached in 23.40 s"
  std::string numbers;  ///< "path 5.12 m · min clearance 0.081 m · 4 switches · 2340 steps"
};

Caption run_caption(const Scenario& scenario, const RunResult& result);
Caption fleet_caption(const Scenario& scenario, const FleetResult& result);

}  // namespace floornav::render_detail
