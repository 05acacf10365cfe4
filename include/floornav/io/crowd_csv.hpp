#pragma once
/// @file
/// crowd.csv, written beside a fleet's trajectory.csv when the scenario has people or forklifts:
/// header `t,kind,name,x,y,theta`, then every recorded state of every person (kind `person`) and
/// forklift (kind `forklift`), one after another (m, rad; theta is the walking or driving
/// direction). What a replay needs to draw them: people are discs of the summary's radii (the
/// scenario's), forklifts rectangles of their size centred at (x, y), turned by theta.

#include <string>

#include "floornav/sim/crowd.hpp"

namespace floornav {

std::string crowd_to_csv(const CrowdResult& crowd);

}  // namespace floornav
