#pragma once
/// @file
/// floornav::render, pictures of runs: trajectory.svg for a lone robot or a fleet (the world, the
/// paths coloured by mode, the switch points, starts, goals).

#include "floornav/core.hpp"
#include "floornav/render/trajectory_svg.hpp"
