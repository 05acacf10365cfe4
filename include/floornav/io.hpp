#pragma once
/// @file
/// floornav::io, everything that reads or writes files: scenario files (YAML, strict: errors
/// name the file, line and key), the map formats (ROS map_server, MovingAI, Gazebo worlds, the
/// course simulator's worlds, BARN), summary.json and trajectory.csv, atomic file writes.

#include "floornav/core.hpp"
#include "floornav/io/atomic_file.hpp"
#include "floornav/io/barn.hpp"
#include "floornav/io/course_world.hpp"
#include "floornav/io/crowd_csv.hpp"
#include "floornav/io/movingai_map.hpp"
#include "floornav/io/provenance.hpp"
#include "floornav/io/ros_map.hpp"
#include "floornav/io/run_mcap.hpp"
#include "floornav/io/scenario_file.hpp"
#include "floornav/io/scenario_writer.hpp"
#include "floornav/io/sdf_world.hpp"
#include "floornav/io/summary_json.hpp"
#include "floornav/io/trajectory_csv.hpp"
