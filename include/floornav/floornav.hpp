#pragma once
/// @file
/// Everything floornav offers, for programs that link floornav::floornav: load a scenario
/// (io/scenario_file.hpp), plug in a controller of your own (nav/controller.hpp,
/// nav/automaton_controller.hpp on the hybrid automaton engine), run it (scenario/simulate.hpp),
/// and write or print what happened (runner/run_outputs.hpp). docs/CONTROLLERS.md explains how
/// to write a controller; examples/ holds complete programs.

#include "floornav/core.hpp"
#include "floornav/io.hpp"
#include "floornav/render.hpp"
#include "floornav/runner.hpp"
