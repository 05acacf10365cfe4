#pragma once
/// @file
/// floornav::render, pictures of runs: trajectory.svg for a lone robot or a fleet (the world, the
/// paths coloured by mode or by robot, the switch points, starts, numbered goals, footprints),
/// trajectory.html (the replay in a browser), and the colours both use.

#include "floornav/core.hpp"
#include "floornav/render/frame_raster.hpp"
#include "floornav/render/palette.hpp"
#include "floornav/render/trajectory_html.hpp"
#include "floornav/render/trajectory_svg.hpp"
