#pragma once
/// @file
/// run.mcap: a run as a ROS 2 bag (MCAP, profile `ros2`, `ros2msg` schemas, `cdr` messages;
/// CONTRACT.md "MCAP (ROS 2 bag)"), for Foxglove, Lichtblick and `ros2 bag play`. Log time =
/// publish time = header stamp = simulated time in nanoseconds. Every channel is listed in
/// docs/OUTPUTS.md; a fleet's robot topics are prefixed with `/<robot name>` and its frames with
/// `<robot name>/`.
///
/// Per robot: `/odom` (nav_msgs/msg/Odometry, one per trajectory row), `/tf` (odom -> base_link
/// at every row) and `/tf_static` (map -> odom, identity; base_link -> each sensor frame), the
/// sensors at the recorded range frames (RunResult::ranges) at most every kMcapSensorPeriod:
/// `/scan`, `/scan_1`, ... for lidars,
/// `/ring_scan` for a ring of IR or sonar sensors, `/range` for a lone one, `/mode` and
/// `/transition` (std_msgs/msg/String), `/goal` (geometry_msgs/msg/PoseStamped), `/body`
/// (visualization_msgs/msg/MarkerArray, the footprint, once). Once for the run: `/map`
/// (nav_msgs/msg/OccupancyGrid), `/world` (the shapes as markers); `/clock` at every step;
/// `/crowd` (people and forklifts as markers, 10 times a simulated second) when there are any.

#include <functional>
#include <string_view>

#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// Ranges a run records at most for its bag (over all robots and frames): 80 MB of floats.
inline constexpr double kMaxMcapRangeValues = 2e7;
/// s: the bag's sensor topics publish at most this often (10 Hz, a typical lidar's rate; a run
/// senses every step, 100 times a second at dt = 0.01).
inline constexpr double kMcapSensorPeriod = 0.1;

/// Where a bag goes: the bytes of the file, piece by piece, in order.
using McapSink = std::function<void(std::string_view)>;

/// The sim.record_ranges_every a run of `scenario` needs for its bag's sensor topics: the steps
/// closest to kMcapSensorPeriod (at least 1), more while the robots' sensors over t_max would pass
/// kMaxMcapRangeValues. 0 when no robot has a sensor.
int mcap_ranges_interval(const Scenario& scenario);

/// The bag of one robot's run (`result.trajectory` recorded), handed to `sink` in pieces.
void write_run_mcap(const Scenario& scenario, const RunResult& result, const McapSink& sink);

/// The bag of a fleet (every robot, and the people and forklifts).
void write_fleet_mcap(const Scenario& scenario, const FleetResult& result, const McapSink& sink);

}  // namespace floornav
