#pragma once
/// @file
/// floornav::runner, what runs scenarios and writes their files: a run's outputs (summary.json,
/// trajectory.csv, trajectory.svg) and its one-line report, batches of runs in parallel, the
/// optimum of a scenario (the grid optimum behind `path_efficiency`).

#include "floornav/io.hpp"
#include "floornav/render.hpp"
#include "floornav/runner/batch.hpp"
#include "floornav/runner/run_outputs.hpp"
#include "floornav/runner/run_summary.hpp"
#include "floornav/runner/scenario_optimum.hpp"
