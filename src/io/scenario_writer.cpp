#include "floornav/io/scenario_writer.hpp"

#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "floornav/core/enum_names.hpp"
#include "floornav/core/param_fields.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/robot/robot_spec.hpp"

namespace floornav {

namespace {

using Json = nlohmann::ordered_json;

/// The archive of visit_fields (core/param_fields.hpp) that writes each field into a JSON object:
/// the values first, then the sections, each section a nested object.
class JsonWriter {
 public:
  explicit JsonWriter(Json& out) : out_(out) {}

  /// Writes the fields of `value` into the object, sections last.
  template <class T>
  void write(const T& value) {
    visit_fields(value, *this);
    for (auto& [key, j] : sections_) out_[key] = std::move(j);
    sections_.clear();
  }

  template <class T>
  void operator()(const char* key, const T& field, const char* /*doc*/) {
    if constexpr (NamedEnum<T>)
      out_[key] = std::string(to_string(field));  // by its name, as the reader takes it
    else
      out_[key] = field;
  }
  template <class T>
  void section(const char* key, const T& sub) {
    Json j = Json::object();
    JsonWriter(j).write(sub);
    sections_.emplace_back(key, std::move(j));
  }

 private:
  Json& out_;
  std::vector<std::pair<const char*, Json>> sections_;
};

template <class T>
Json fields_of(const T& value) {
  Json j = Json::object();
  JsonWriter(j).write(value);
  return j;
}

Json point(const Vec2& p) {
  return Json::array({p.x(), p.y()});
}
Json pose(const Pose2& p) {
  return Json::array({p.position.x(), p.position.y(), p.theta});
}
Json points(std::span<const Vec2> pts) {
  Json j = Json::array();
  for (const Vec2& p : pts) j.push_back(point(p));
  return j;
}

bool same_spec(const RangeSensorSpec& a, const RangeSensorSpec& b) {
  return a.mount.position == b.mount.position && a.mount.theta == b.mount.theta &&
         a.min_range == b.min_range && a.max_range == b.max_range && a.cone_angle == b.cone_angle &&
         a.cone_rays == b.cone_rays;
}

/// `x` moved by `k` representable doubles (k may be negative).
double nudged(double x, int k) {
  for (; k > 0; --k) x = std::nextafter(x, HUGE_VAL);
  for (; k < 0; ++k) x = std::nextafter(x, -HUGE_VAL);
  return x;
}

/// The `lidar:` section that make_lidar turns back into exactly `sensors`, if there is one: the
/// field of view and the mount's heading are recovered from the beams' headings and checked by
/// making the lidar again and comparing every beam bit for bit.
std::optional<Json> as_lidar(const std::vector<RangeSensorSpec>& sensors) {
  const std::size_t n = sensors.size();
  if (n == 0) return std::nullopt;
  const RangeSensorSpec& s0 = sensors.front();
  for (const RangeSensorSpec& s : sensors)
    if (s.mount.position != s0.mount.position || s.min_range != s0.min_range ||
        s.max_range != s0.max_range || s.cone_angle != 0.0 || s.cone_rays != 1)
      return std::nullopt;
  const double h0 = s0.mount.theta;
  const double step = n > 1 ? wrap_angle(sensors[1].mount.theta - h0) : 0.0;
  // (fov, mount heading) guesses, the likeliest first: a full circle; a fan centred on heading 0;
  // a fan centred on the heading its ends imply; each nudged by a few units in the last place.
  std::vector<std::pair<double, double>> guesses;
  for (const double full : {2.0 * kPi, 6.283185307}) guesses.emplace_back(full, h0);
  if (n > 1) {
    guesses.emplace_back(-2.0 * h0, 0.0);
    const double fov = step * static_cast<double>(n - 1);
    guesses.emplace_back(fov, wrap_angle(h0 + 0.5 * fov));
    guesses.emplace_back(step * static_cast<double>(n), h0);  // full circle by another name
  }
  const std::size_t plain = guesses.size();
  for (std::size_t g = 0; g < plain; ++g)
    for (int k = -6; k <= 6; ++k)
      for (int m = -3; m <= 3; ++m)
        if (k != 0 || m != 0)
          guesses.emplace_back(nudged(guesses[g].first, k), nudged(guesses[g].second, m));
  for (const auto& [fov, heading] : guesses) {
    if (!(fov > 0.0) || fov > 2.0 * kPi + 1e-9) continue;
    const auto made = make_lidar(static_cast<int>(n), fov, s0.min_range, s0.max_range,
                                 {s0.mount.position, heading});
    bool same = true;
    for (std::size_t i = 0; i < n && same; ++i) same = same_spec(made[i], sensors[i]);
    if (!same) continue;
    Json lidar = Json::object();
    lidar["beams"] = n;
    lidar["fov"] = fov;
    lidar["min_range"] = s0.min_range;
    lidar["max_range"] = s0.max_range;
    lidar["mount"] = pose({s0.mount.position, heading});
    return lidar;
  }
  return std::nullopt;
}

Json sensors_json(const RobotSpec& r) {
  Json j = Json::object();
  if (auto lidar = as_lidar(r.sensors)) {
    j["lidar"] = std::move(*lidar);
  } else if (!r.sensors.empty()) {
    Json mounts = Json::array();
    for (const RangeSensorSpec& s : r.sensors) mounts.push_back(pose(s.mount));
    j["mounts"] = std::move(mounts);
    // A file gives these once for every sensor; the first sensor's stand for all.
    const RangeSensorSpec& s0 = r.sensors.front();
    j["min_range"] = s0.min_range;
    j["max_range"] = s0.max_range;
    j["cone_angle"] = s0.cone_angle;
    j["cone_rays"] = s0.cone_rays;
  }
  j["noise"] = r.sensor_noise;
  return j;
}

/// A robot section's keys (without goals and controller).
Json robot_json(const RobotTask& t) {
  const RobotSpec& r = t.robot;
  Json j = Json::object();
  j["preset"] = r.preset.empty() ? std::string("quickbot") : r.preset;
  j["start"] = pose(t.start);
  j["radius"] = r.body_radius;
  j["wheel_radius"] = r.drive.wheel_radius;
  j["track_width"] = r.drive.track_width;
  j["max_wheel_speed"] = r.drive.max_wheel_speed;
  j["min_wheel_speed"] = r.drive.min_wheel_speed;
  j["footprint"] = points(r.footprint);
  j["sensors"] = sensors_json(r);
  return j;
}

void put_goals(Json& j, const std::vector<Vec2>& goals) {
  if (goals.size() == 1)
    j["goal"] = point(goals.front());
  else
    j["goals"] = points(goals);
}

Json controller_json(const ControllerConfig& c) {
  Json j = Json::object();
  j["kind"] = c.kind;
  // summary.json's config has always led with the kind and robot_avoidance: a key placed here
  // keeps its place when the listing writes its value.
  j["robot_avoidance"] = nullptr;
  JsonWriter(j).write(c);
  return j;
}

Json world_json(const Scenario& s) {
  Json j = Json::object();
  if (!s.world) return j;
  const World& w = *s.world;
  if (w.bounds())
    j["bounds"] = Json::array(
        {w.bounds()->min.x(), w.bounds()->min.y(), w.bounds()->max.x(), w.bounds()->max.y()});
  // The file's own obstacles come first; those the map added (SDF, course XML) are the map's.
  const std::size_t own_circles =
      w.circles().size() - (s.world_map ? std::min(s.world_map->circles, w.circles().size()) : 0);
  const std::size_t own_polygons =
      w.polygons().size() -
      (s.world_map ? std::min(s.world_map->polygons, w.polygons().size()) : 0);
  Json obstacles = Json::array();
  for (std::size_t i = 0; i < own_circles; ++i) {
    Json c = Json::object();
    c["center"] = point(w.circles()[i].center);
    c["radius"] = w.circles()[i].radius;
    obstacles.push_back(Json{{"circle", std::move(c)}});
  }
  for (std::size_t i = 0; i < own_polygons; ++i)
    obstacles.push_back(Json{{"polygon", points(w.polygons()[i])}});
  if (!obstacles.empty()) j["obstacles"] = std::move(obstacles);
  if (s.world_map) {
    j["map"] = s.world_map->path;
    if (s.world_map->cell_size > 0.0) j["cell_size"] = s.world_map->cell_size;
    if (!s.world_map->unknown.empty()) j["unknown"] = s.world_map->unknown;
  }
  return j;
}

bool is_flat(const Json& v) {
  if (!v.is_array()) return !v.is_object() || v.empty();
  for (const Json& e : v)
    if (e.is_object() || (e.is_array() && !is_flat(e))) return false;
  return true;
}

std::string scalar(const Json& v) {
  if (v.is_number_float()) return fmt::format("{}", v.get<double>());
  if (v.is_string()) return v.dump();  // a JSON string is a YAML double-quoted string
  if (v.is_null()) return "null";
  return v.dump();  // integers, booleans
}

std::string flow(const Json& v) {
  if (v.is_array()) {
    std::string out = "[";
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (i) out += ", ";
      out += flow(v[i]);
    }
    return out + "]";
  }
  if (v.is_object()) return "{}";
  return scalar(v);
}

void block(const Json& v, std::size_t indent, std::string& out) {
  const std::string pad(indent, ' ');
  for (const auto& [key, value] : v.items()) {
    out += pad + key + ":";
    if (is_flat(value)) {
      out += ' ';
      out += flow(value);
      out += '\n';
    } else if (value.is_object()) {
      out += "\n";
      block(value, indent + 2, out);
    } else {  // a list of mappings (obstacles, robots): "- first: ..." then the rest below it
      out += "\n";
      for (const Json& item : value) {
        std::string text;
        if (item.is_object()) {
          block(item, indent + 4, text);
          text.replace(indent, 4, "  - ");
        } else {
          text.assign(indent + 2, ' ');
          text += "- ";
          text += flow(item);
          text += '\n';
        }
        out += text;
      }
    }
  }
}

}  // namespace

nlohmann::ordered_json scenario_to_json(const Scenario& s) {
  Json j = Json::object();
  j["name"] = s.name;
  j["world"] = world_json(s);
  if (s.robots_listed || s.robots.size() != 1) {
    Json robots = Json::array();
    for (const RobotTask& t : s.robots) {
      Json r = Json::object();
      r["name"] = t.name;
      const Json robot = robot_json(t);
      for (const auto& [k, v] : robot.items()) r[k] = v;
      put_goals(r, t.goals);
      r["controller"] = controller_json(t.controller);
      robots.push_back(std::move(r));
    }
    j["robots"] = std::move(robots);
  } else if (!s.robots.empty()) {
    j["robot"] = robot_json(s.robot());
    put_goals(j, s.robot().goals);
    j["controller"] = controller_json(s.robot().controller);
  }
  j["sim"] = fields_of(s.sim);
  // People and forklifts, every value explicit (a people_file's agents are written out).
  if (!s.crowd.people.empty()) {
    Json people = Json::array();
    for (const PersonSpec& p : s.crowd.people)
      people.push_back(Json{{"name", p.name},
                            {"start", point(p.start)},
                            {"waypoints", points(p.waypoints)},
                            {"speed", p.speed},
                            {"radius", p.radius},
                            {"goal_radius", p.goal_radius},
                            {"cyclic", p.cyclic}});
    j["people"] = std::move(people);
  }
  if (!s.crowd.forklifts.empty()) {
    Json forklifts = Json::array();
    for (const ForkliftSpec& f : s.crowd.forklifts)
      forklifts.push_back(Json{{"name", f.name},
                               {"route", points(f.route)},
                               {"speed", f.speed},
                               {"size", point(f.size)},
                               {"stop_distance", f.stop_distance},
                               {"cyclic", f.cyclic}});
    j["forklifts"] = std::move(forklifts);
  }
  return j;
}

std::string json_to_yaml(const nlohmann::ordered_json& value) {
  if (!value.is_object()) return flow(value) + "\n";
  std::string out;
  block(value, 0, out);
  return out;
}

std::string scenario_to_yaml(const Scenario& s) {
  return "# The resolved scenario (presets and overrides applied, every value explicit), as "
         "written "
         "by floornav.\n# `floornav run` on this file repeats the run.\n" +
         json_to_yaml(scenario_to_json(s));
}

}  // namespace floornav
