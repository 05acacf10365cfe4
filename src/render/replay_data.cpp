#include "replay_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "floornav/render/palette.hpp"
#include "floornav/render/trajectory_html.hpp"
#include "floornav/sim/goal_rows.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "replay_track.hpp"

namespace floornav::render_detail {

namespace {

using Json = nlohmann::ordered_json;

constexpr std::int64_t kMaxGridCells = 4'000'000;
constexpr double kAngleUnit = 1e-4;  ///< rad per stored heading unit

/// m -> whole millimetres (non-finite: 0).
std::int64_t mm(double v) {
  return std::isfinite(v) ? std::llround(v * 1000.0) : 0;
}

/// A length for the world's shapes: rounded to the micrometre, so that JSON prints it short.
double micro(double v) {
  return std::isfinite(v) ? std::round(v * 1e6) / 1e6 + 0.0 : 0.0;
}

/// Appends `values` delta-coded (first value, then differences).
Json deltas(const std::vector<std::int64_t>& values) {
  Json out = Json::array();
  std::int64_t previous = 0;
  for (std::int64_t v : values) {
    out.push_back(v - previous);
    previous = v;
  }
  return out;
}

/// Headings in kAngleUnit, unwrapped (each the previous plus the short-way difference), so that
/// interpolating between two stored headings turns the right way.
std::vector<std::int64_t> unwrapped_angles(const std::vector<double>& angles) {
  std::vector<std::int64_t> out;
  out.reserve(angles.size());
  double previous = 0.0, sum = 0.0;
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const double a = std::isfinite(angles[i]) ? angles[i] : previous;
    sum = i == 0 ? a : sum + std::remainder(a - previous, 2.0 * std::numbers::pi);
    previous = a;
    out.push_back(std::llround(sum / kAngleUnit));
  }
  return out;
}

/// {k, x, y, th} of the given rows of a pose series.
Json pose_series(const std::vector<std::int64_t>& rows, const std::vector<double>& xs,
                 const std::vector<double>& ys, const std::vector<double>& ths) {
  std::vector<std::int64_t> x, y;
  for (double v : xs) x.push_back(mm(v));
  for (double v : ys) y.push_back(mm(v));
  Json j;
  j["k"] = deltas(rows);
  j["x"] = deltas(x);
  j["y"] = deltas(y);
  j["th"] = deltas(unwrapped_angles(ths));
  return j;
}

Json world_json(const World* world) {
  Json w;
  w["bounds"] = nullptr;
  w["circles"] = Json::array();
  w["polygons"] = Json::array();
  w["grid"] = nullptr;
  if (!world) return w;
  if (const auto& b = world->bounds())
    w["bounds"] = {micro(b->min.x()), micro(b->min.y()), micro(b->max.x()), micro(b->max.y())};
  for (const Circle& c : world->circles())
    w["circles"].push_back({micro(c.center.x()), micro(c.center.y()), micro(c.radius)});
  for (const auto& poly : world->polygons()) {
    Json p = Json::array();
    for (const Vec2& v : poly) {
      p.push_back(micro(v.x()));
      p.push_back(micro(v.y()));
    }
    w["polygons"].push_back(std::move(p));
  }
  if (const OccupancyGrid* g = world->grid()) {
    // Blocks of k x k cells for big maps (occupied when any cell is, else unknown when any is).
    int k = 1;
    while ((static_cast<std::int64_t>(g->width()) + k - 1) / k *
               ((static_cast<std::int64_t>(g->height()) + k - 1) / k) >
           kMaxGridCells)
      ++k;
    const int bw = (g->width() + k - 1) / k, bh = (g->height() + k - 1) / k;
    std::vector<std::uint8_t> cells(static_cast<std::size_t>(bw) * static_cast<std::size_t>(bh), 0);
    for (int iy = 0; iy < g->height(); ++iy)
      for (int ix = 0; ix < g->width(); ++ix) {
        // An unknown cell is shown as unknown, whatever the loader's policy made of it.
        const std::uint8_t c = g->unknown(ix, iy) ? 2 : g->occupied(ix, iy) ? 1 : 0;
        std::uint8_t& b = cells[static_cast<std::size_t>(iy / k) * static_cast<std::size_t>(bw) +
                                static_cast<std::size_t>(ix / k)];
        if (c == 1 || (c == 2 && b == 0)) b = c;
      }
    Json rle = Json::array();
    for (std::size_t i = 0; i < cells.size();) {
      std::size_t j = i;
      while (j < cells.size() && cells[j] == cells[i]) ++j;
      rle.push_back(cells[i]);
      rle.push_back(j - i);
      i = j;
    }
    Json grid;
    grid["width"] = bw;
    grid["height"] = bh;
    grid["resolution"] = g->resolution() * k;
    grid["origin"] = {micro(g->origin().position.x()), micro(g->origin().position.y()),
                      g->origin().theta};
    grid["block"] = k;
    grid["rle"] = std::move(rle);
    w["grid"] = std::move(grid);
  }
  return w;
}

/// The recorded beam frames of `r` the replay shows: each at least `gap` steps after the last one
/// taken, so that a run recording more often for its bag (run.mcap) shows what it would without.
std::vector<std::size_t> beam_frames(const RobotTask& task, const RunResult& r, int gap) {
  std::vector<std::size_t> out;
  const std::size_t sensors = task.robot.sensors.size();
  if (sensors == 0 || r.range_steps.empty() || r.ranges.size() != r.range_steps.size() * sensors)
    return out;
  std::int64_t next = 0;
  for (std::size_t f = 0; f < r.range_steps.size(); ++f) {
    if (r.range_steps[f] < next) continue;
    out.push_back(f);
    next = r.range_steps[f] + std::max(gap, 1);
  }
  return out;
}

/// The beam frames `frames` of `r`, every `stride`-th one.
Json beams_json(const RobotTask& task, const RunResult& r, std::span<const std::size_t> frames,
                std::size_t stride) {
  const std::size_t sensors = task.robot.sensors.size();
  if (frames.empty()) return nullptr;
  std::vector<std::int64_t> rows;
  std::vector<double> xs, ys, ths;
  Json ranges = Json::array();
  for (std::size_t k = 0; k < frames.size(); k += stride) {
    const std::size_t f = frames[k];
    const auto row = static_cast<std::size_t>(r.range_steps[f]);
    if (row >= r.trajectory.size()) break;
    const TrajectorySample& s = r.trajectory[row];
    rows.push_back(static_cast<std::int64_t>(row));
    xs.push_back(s.x);
    ys.push_back(s.y);
    ths.push_back(s.theta);
    for (std::size_t i = 0; i < sensors; ++i) {
      const double range = r.ranges[f * sensors + i];
      const bool seen = std::isfinite(range) && range < task.robot.sensors[i].max_range - 1e-6;
      ranges.push_back(seen ? mm(range) : -1);
    }
  }
  Json j = pose_series(rows, xs, ys, ths);
  j["r"] = std::move(ranges);
  return j;
}

Json robot_json(const Track& t, const SimConfig& sim, std::span<const std::size_t> beam_frames,
                std::size_t beam_stride) {
  const RobotTask& task = *t.task;
  const RunResult& r = *t.run;
  Json j;
  j["name"] = r.scenario.empty() ? task.name : r.scenario;
  j["color"] = t.color;
  j["radius"] = task.robot.body_radius;
  if (task.robot.footprint.size() >= 3) {
    Json f = Json::array();
    for (const Vec2& v : task.robot.footprint) {
      f.push_back(micro(v.x()));
      f.push_back(micro(v.y()));
    }
    j["footprint"] = std::move(f);
  } else {
    j["footprint"] = nullptr;
  }
  const NavigationParams& nav = task.controller.params;
  j["d_o"] = nav.d_o;
  j["footprint_clearance"] = nav.footprint_clearance;
  j["epsilon"] = nav.epsilon;
  j["start"] = {micro(task.start.position.x()), micro(task.start.position.y()), task.start.theta};
  j["goals"] = Json::array();
  for (const Vec2& g : task.goals) j["goals"].push_back({micro(g.x()), micro(g.y())});
  j["goal_rows"] = goal_reached_rows(task, r);
  j["status"] = std::string(to_string(r.status));
  j["collided"] = r.collided;
  j["parked"] = sim.park_finished || r.collided;
  j["rows"] = r.trajectory.size();
  j["modes"] = r.mode_names;
  j["guards"] = r.guard_names;

  const std::vector<std::size_t> kept = decimate_track(r.trajectory);
  std::vector<std::int64_t> rows;
  std::vector<double> xs, ys, ths;
  for (std::size_t i : kept) {
    const TrajectorySample& s = r.trajectory[i];
    rows.push_back(static_cast<std::int64_t>(i));
    xs.push_back(s.x);
    ys.push_back(s.y);
    ths.push_back(s.theta);
  }
  j["track"] = pose_series(rows, xs, ys, ths);

  Json runs = Json::array();
  for (std::size_t i = 0; i < r.trajectory.size(); ++i)
    if (i == 0 || r.trajectory[i].mode != r.trajectory[i - 1].mode) {
      runs.push_back(i);
      runs.push_back(r.trajectory[i].mode);
    }
  j["mode_runs"] = std::move(runs);

  Json switches = Json::array();
  for (const Transition& tr : r.transitions) {
    switches.push_back(std::llround(tr.time / sim.dt));
    switches.push_back(tr.from);
    switches.push_back(tr.to);
    switches.push_back(tr.edge);
  }
  j["switches"] = std::move(switches);

  Json sensors = Json::array();
  for (const RangeSensorSpec& s : task.robot.sensors)
    sensors.push_back({micro(s.mount.position.x()), micro(s.mount.position.y()), s.mount.theta,
                       s.max_range, s.cone_angle});
  j["sensors"] = std::move(sensors);
  j["beams"] = beams_json(task, r, beam_frames, beam_stride);
  return j;
}

/// One person's or forklift's samples, every `stride`-th one and the last, as rows of the run.
Json crowd_track_json(const CrowdTrack& t, const SimConfig& sim, std::size_t stride) {
  std::vector<std::int64_t> rows;
  std::vector<double> xs, ys, ths;
  for (std::size_t i = 0; i < t.samples.size(); ++i) {
    if (i % stride != 0 && i + 1 != t.samples.size()) continue;
    const CrowdSample& c = t.samples[i];
    const std::int64_t row = std::isfinite(c.t / sim.dt) ? std::llround(c.t / sim.dt) : 0;
    if (!rows.empty() && row <= rows.back()) continue;  // rows strictly increase
    rows.push_back(row);
    xs.push_back(c.x);
    ys.push_back(c.y);
    ths.push_back(c.theta);
  }
  Json j;
  j["name"] = t.name;
  j["size"] = {micro(t.size.x()), micro(t.size.y())};
  j["track"] = pose_series(rows, xs, ys, ths);
  return j;
}

Json crowd_json(const CrowdResult& c, const SimConfig& sim) {
  std::size_t samples = 0;
  for (const auto* group : {&c.people, &c.forklifts})
    for (const CrowdTrack& t : *group) samples += t.samples.size();
  const std::size_t stride =
      std::max<std::size_t>(1, (samples + kMaxReplayCrowdSamples - 1) / kMaxReplayCrowdSamples);
  Json j;
  j["people"] = Json::array();
  for (const CrowdTrack& t : c.people) j["people"].push_back(crowd_track_json(t, sim, stride));
  j["forklifts"] = Json::array();
  for (const CrowdTrack& t : c.forklifts)
    j["forklifts"].push_back(crowd_track_json(t, sim, stride));
  j["person_contacts"] = c.metrics.person_contacts;
  j["forklift_contacts"] = c.metrics.forklift_contacts;
  j["intrusions"] = c.metrics.intrusions;
  return j;
}

}  // namespace

Json replay_data(const World* world, std::span<const Track> tracks, const SimConfig& sim,
                 int beam_gap, const Caption& caption, std::string_view status, double duration,
                 const CrowdResult* crowd) {
  Json j;
  j["format"] = "floornav-replay";
  j["version"] = 1;
  j["title"] = caption.title;
  j["numbers"] = caption.numbers;
  j["status"] = std::string(status);
  j["dt"] = sim.dt;
  const double rate = std::round(1.0 / sim.dt);
  j["rate"] = rate >= 1.0 && std::abs(rate * sim.dt - 1.0) < 1e-12 ? Json(rate) : Json(nullptr);
  j["duration"] = duration;
  const Extent e = picture_extent(world, tracks);
  j["extent"] = {e.xmin, e.ymin, e.xmax, e.ymax};
  Json colors = Json::object();
  for (const Track& t : tracks)
    for (std::size_t m = 0; m < t.run->mode_names.size(); ++m)
      colors[t.run->mode_names[m]] =
          std::string(mode_color_of(t.run->mode_names, static_cast<int>(m)));
  j["mode_colors"] = std::move(colors);
  j["world"] = world_json(world);

  // Beam frames beyond the budget are thinned evenly, the same stride for every robot.
  std::vector<std::vector<std::size_t>> frames;
  std::size_t range_values = 0;
  for (const Track& t : tracks) {
    frames.push_back(beam_frames(*t.task, *t.run, beam_gap));
    range_values += frames.back().size() * t.task->robot.sensors.size();
  }
  const std::size_t stride =
      std::max<std::size_t>(1, (range_values + kMaxReplayRangeValues - 1) / kMaxReplayRangeValues);
  Json robots = Json::array();
  for (std::size_t i = 0; i < tracks.size(); ++i)
    robots.push_back(robot_json(tracks[i], sim, frames[i], stride));
  j["robots"] = std::move(robots);
  j["crowd"] = crowd && !crowd->empty() ? crowd_json(*crowd, sim) : Json(nullptr);
  return j;
}

}  // namespace floornav::render_detail
