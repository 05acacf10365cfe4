#pragma once
/// @file
/// How often a run may record its sensors' ranges (sim.record_ranges_every) to stay within a
/// budget of values: what the HTML replay and the ROS 2 bag each ask for.

#include "floornav/scenario/scenario.hpp"

namespace floornav {

/// Every step when all robots' sensors over t_max fit `max_values` ranges, else the fewest steps
/// apart that fit; 0 when no robot has a sensor.
int ranges_interval_within(const Scenario& scenario, double max_values);

}  // namespace floornav
