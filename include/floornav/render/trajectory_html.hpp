#pragma once
/// @file
/// trajectory.html (CONTRACT.md): one self-contained page (data, script and style inline;
/// nothing fetched) that replays a run in a browser: the world (the map as an image, unknown
/// cells apart from obstacles), every robot's footprint with its heading, its trail (coloured by
/// mode; in a fleet by robot, the mode on the body), the sensor beams and sensed points, the d_o
/// band, each robot's current goal, and a timeline of modes with a tick per switch. It exposes
/// `window.floornavReplay` with `duration`, `seek(t)` and `state()`.
///
/// Positions are kept where linear interpolation in time would miss a recorded row by more than
/// 9 mm or 0.01 rad (stored in millimetres, so what the page shows at a recorded time is within
/// 1 cm of trajectory.csv). The beams come from RunResult::ranges (sim.record_ranges_every; a
/// run without them shows no beams), thinned to at most kMaxReplayRangeValues ranges. A fleet's
/// people (discs) and forklifts (rectangles) move with the robots, from FleetResult::crowd, at
/// most kMaxReplayCrowdSamples positions in all (every n-th step, linear in between).

#include <cstddef>
#include <string>

#include "floornav/scenario/scenario.hpp"
#include "floornav/sim/fleet_simulation.hpp"
#include "floornav/sim/run_result.hpp"

namespace floornav {

/// Ranges a replay holds at most (over all robots and frames): about 1.5 MB of the file.
inline constexpr std::size_t kMaxReplayRangeValues = 300'000;
/// People's and forklifts' positions a replay holds at most (all of them together).
inline constexpr std::size_t kMaxReplayCrowdSamples = 200'000;

/// The sim.record_ranges_every that a run of `scenario` needs for its replay's beams: every
/// step when the robots' sensors over t_max fit kMaxReplayRangeValues, else the fewest steps
/// apart that fit. 0 when no robot has a sensor.
int replay_ranges_interval(const Scenario& scenario);

/// The page for one robot's run (`result.trajectory` recorded).
std::string render_trajectory_html(const Scenario& scenario, const RunResult& result);

/// The page for a fleet: every robot in its colour (robot_color), the mode on its body.
std::string render_fleet_html(const Scenario& scenario, const FleetResult& result);

}  // namespace floornav
