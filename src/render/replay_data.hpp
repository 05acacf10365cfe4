#pragma once
/// @file
/// Private to the render module: the data of an HTML replay, as the JSON object the page reads
/// (src/render/replay/replay_core.js decodes it). Lengths in millimetres and headings in
/// 1e-4 rad, as integers, and every long series delta-coded, so that a 10-minute run or a
/// 100-robot fleet stays a few megabytes.
///
/// {format: "floornav-replay", version: 1, title, numbers, status, dt, rate (steps per second
///  when 1/dt is whole, else null), duration (s), extent [xmin, ymin, xmax, ymax] (m),
///  mode_colors {name: colour},
///  world: {bounds, circles [[x, y, r]], polygons [[x0, y0, x1, y1, ...]], grid: null |
///          {width, height, resolution, origin [x, y, theta], block (cells per pixel),
///           rle [value, count, ...] over rows from the bottom, values 0 free 1 occupied
///           2 unknown}},
///  robots: [{name, color, radius, footprint [x0, y0, ...] | null, d_o, footprint_clearance,
///            epsilon, start [x, y, theta], goals [[x, y]], goal_rows [row reached | -1],
///            status, collided, parked, rows (trajectory rows), modes [names], guards [names],
///            track {k, x, y, th}: kept rows, mm, mm, 1e-4 rad (unwrapped), each delta-coded,
///            mode_runs [row, mode, ...], switches [row, from, to, guard, ...],
///            sensors [[x, y, theta, max_range, cone_angle]],
///            beams {k, x, y, th (delta-coded, as track), r: mm per sensor per frame, -1 for
///                   nothing seen} | null}],
///  crowd: null | {people: [{name, size [length, width] (m), track {k, x, y, th}}],
///                 forklifts: [the same], person_contacts, forklift_contacts, intrusions}}

#include <span>
#include <string>

#include <nlohmann/json.hpp>

#include "floornav/sim/crowd.hpp"
#include "floornav/sim/sim_config.hpp"
#include "picture_layout.hpp"
#include "run_caption.hpp"

namespace floornav::render_detail {

/// The replay of `tracks` in `world` (may be null); `status` and `duration` (s) of the whole run;
/// `crowd`, when given and not empty, the people and forklifts that moved with them. Beam frames
/// are taken at least `beam_gap` steps apart (replay_ranges_interval), then thinned to
/// kMaxReplayRangeValues.
nlohmann::ordered_json replay_data(const World* world, std::span<const Track> tracks,
                                   const SimConfig& sim, int beam_gap, const Caption& caption,
                                   std::string_view status, double duration,
                                   const CrowdResult* crowd = nullptr);

}  // namespace floornav::render_detail
