#pragma once
/// @file
/// floornav::ompl (a build with OMPL): OMPL's RRT-Connect for `planner.kind: rrt_connect`.
/// Not part of floornav/floornav.hpp, so that an install without OMPL has every header that
/// umbrella names.
#include "floornav/ompl/rrt_connect.hpp"
