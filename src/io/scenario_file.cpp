#include "floornav/io/scenario_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <unordered_set>

#include "crowd_file.hpp"
#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/nav/controller_registry.hpp"
#include "floornav/scenario/controller_presets.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/validate.hpp"
#include "input_file.hpp"
#include "utf8_input.hpp"
#include "world_map.hpp"
#include "yaml_reader.hpp"

namespace floornav {

using io_detail::fail;
using io_detail::MapReader;
using io_detail::quote_input;
using io_detail::read_double;
using io_detail::read_point;
using io_detail::read_points;

namespace {

constexpr std::size_t kMaxObstacles = 1000000;
constexpr double kPointPostRadius = 0.03;  // m, the radius given to `point:` obstacles
// The simplicity check is quadratic in a polygon's points: bound the points of one polygon, and
// the sum of their squares over all polygons (YAML aliases can repeat one polygon a million times
// in a small file), so that no file can make it hang. 100 polygons of 1000 points reach it.
constexpr std::size_t kMaxPolygonPoints = 1000;
constexpr std::size_t kMaxPolygonWork = 100000000;  // sum of points^2
// An angle further than this from 0 is a unit mistake (degrees), not a heading.
constexpr double kMaxAngle = 2.0 * kPi + 1e-9;

/// YAML text -> tree. A file is one document: text after it (a second `---` document, anything
/// after `...`, or after a closed flow collection such as `[0, 0, 0] x`) is an error, never
/// silently dropped. Errors name `file` and `where` (a --set), or the line.
YAML::Node parse_yaml(const std::string& text, const std::string& file, const std::string& where) {
  const auto at = [&](const YAML::Mark& m) {
    return where.empty() ? fmt::format("line {}", m.line + 1) : where;
  };
  io_detail::OneDocument doc;
  try {
    doc = io_detail::load_one_document(text);
  } catch (const YAML::DeepRecursion& e) {
    throw InputError(file, at(e.mark), "not valid YAML: the text nests too deeply");
  } catch (const YAML::ParserException& e) {
    throw InputError(file, at(e.mark), "not valid YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(file, where, std::string("not valid YAML: ") + e.what());
  }
  if (doc.second) {
    const YAML::Mark m = *doc.second;
    const std::string rest =
        m.pos >= 0 && static_cast<std::size_t>(m.pos) < text.size() ? text.substr(m.pos) : "";
    throw InputError(file, at(m),
                     where.empty()
                         ? "a second YAML document: a scenario is one document, and nothing may "
                           "follow it (no '---' or '...' with more text after)"
                         : "text after the value: " + quote_input(rest));
  }
  return doc.node;
}

// --- --set overrides ------------------------------------------------------------------------

/// A copy of a mapping or list whose entries are new nodes sharing the old values: assigning to
/// an entry of the copy changes only the copy. (yaml-cpp's aliases are one node in several
/// places: assigning to it in place would change every alias.) Scalars are returned as they are:
/// they are only ever replaced.
YAML::Node shallow_copy(const YAML::Node& n) {
  if (n.IsMap()) {
    YAML::Node out(YAML::NodeType::Map);
    for (const auto& kv : n) out[kv.first] = kv.second;
    return out;
  }
  if (n.IsSequence()) {
    YAML::Node out(YAML::NodeType::Sequence);
    for (std::size_t i = 0; i < n.size(); ++i) {
      out.push_back(YAML::Node(YAML::NodeType::Null));
      out[i] = n[i];
    }
    return out;
  }
  return n;
}

/// Applies one override to `root` (a fresh copy, see shallow_copy): every map and list on the
/// way down is copied before it changes, so that no alias of it elsewhere in the file changes.
/// The copies' handles go to `keep`, which must outlive every use of the tree: yaml-cpp frees a
/// node with the last handle to the memory it was made in, even while the tree still uses it.
void apply_override(YAML::Node& root, const ScenarioOverride& o, std::vector<YAML::Node>& keep) {
  const std::string& assignment = o.assignment;
  auto bad = [&](const std::string& what) { throw InputError(o.file, o.where, what); };
  io_detail::check_utf8_value(assignment, o.file, o.where);
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) bad("expected KEY=VALUE");
  const std::string key = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  YAML::Node value;
  if (o.text) {
    value.reset(YAML::Node(text));  // a string node: never parsed, so nothing in it is syntax
    keep.push_back(value);
  } else {
    try {
      value.reset(parse_yaml(text, o.file, o.where));
      keep.push_back(value);
    } catch (const InputError& e) {
      bad(fmt::format("cannot read value {}: {}", quote_input(text), e.detail));
    }
  }
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) {
    if (part.empty()) bad("empty part in the key path");
    parts.push_back(part);
  }
  if (key.back() == '.') bad("empty part in the key path");
  // A part may index a list, as errors name its entries: `robots[2].start`.
  YAML::Node node = root;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    std::string name = parts[i];
    std::vector<std::size_t> indices;
    while (!name.empty() && name.back() == ']') {
      const auto open = name.rfind('[');
      std::size_t index = 0;
      const std::string digits =
          open == std::string::npos ? "" : name.substr(open + 1, name.size() - open - 2);
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
      if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
        bad(fmt::format("{}: a list index is a number in brackets", quote_input(parts[i])));
      indices.insert(indices.begin(), index);
      name.erase(open);
    }
    if (name.empty()) bad("empty part in the key path");
    if (!node.IsMap())
      bad(fmt::format("{} is not a mapping, cannot set a key inside it",
                      i > 0 ? quote_input(parts[i - 1]) : std::string("the scenario")));
    const bool last = i + 1 == parts.size();
    if (last && indices.empty()) {
      // `goal` and `goals` are alternatives: setting one replaces the other.
      if (name == "goal" || name == "goals") node.remove(name == "goal" ? "goals" : "goal");
      node[name] = value;
      return;
    }
    // (Handles are rebound with reset(): assigning one yaml-cpp node to another would rewrite
    // the node itself, wherever else it appears.)
    const YAML::Node& cnode = node;
    const YAML::Node existing = cnode[name];
    if (!indices.empty() && (!existing.IsDefined() || !existing.IsSequence()))
      bad(fmt::format("{} has no entry [{}] (not a list)", quote_input(name), indices[0]));
    YAML::Node child = indices.empty() && (!existing.IsDefined() || existing.IsNull())
                           ? YAML::Node(YAML::NodeType::Map)
                           : shallow_copy(existing);
    keep.push_back(child);
    node[name] = child;
    std::string path = name;
    for (std::size_t k = 0; k < indices.size(); ++k) {
      if (!child.IsSequence() || indices[k] >= child.size())
        bad(fmt::format(
            "{} has no entry [{}] ({})", quote_input(path), indices[k],
            child.IsSequence() ? fmt::format("it has {}", child.size()) : "not a list"));
      if (last && k + 1 == indices.size()) {
        child[indices[k]] = value;
        return;
      }
      path += fmt::format("[{}]", indices[k]);
      YAML::Node element = shallow_copy(child[indices[k]]);
      keep.push_back(element);
      child[indices[k]] = element;
      child.reset(element);
    }
    node.reset(child);
  }
}

// --- sections -------------------------------------------------------------------------------

/// An angle in radians, refused beyond +-2 pi: such a number is nearly always degrees.
double check_angle(const std::string& file, const YAML::Node& n, const std::string& key,
                   double angle) {
  if (std::abs(angle) > kMaxAngle)
    fail(file, n, key,
         fmt::format("{:.6g} is beyond +-2 pi: angles are in radians (if you meant {:.6g} "
                     "degrees, write {:.6g})",
                     angle, angle, deg_to_rad(angle)));
  return angle;
}

Pose2 read_pose(const std::string& file, const YAML::Node& n, const std::string& key) {
  const auto v = io_detail::read_numbers(file, n, key, 3);
  return {Vec2(v[0], v[1]), check_angle(file, n[2], key + "[2]", v[2])};
}

double read_positive(const std::string& file, const YAML::Node& n, const std::string& key) {
  const double v = read_double(file, n, key);
  if (v <= 0.0) fail(file, n, key, fmt::format("must be positive, got {:.6g}", v));
  return v;
}

void read_obstacle(const std::string& file, const YAML::Node& item, const std::string& key,
                   WorldDesc& desc, std::size_t& polygon_work) {
  MapReader r(file, item, key);
  int kinds = 0;
  if (r.has("circle")) {
    ++kinds;
    MapReader c = r.sub("circle");
    Circle circle;
    circle.center = read_point(file, c.require("center", "[x, y]"), c.path_of("center"));
    circle.radius = read_positive(file, c.require("radius", "m"), c.path_of("radius"));
    c.finish();
    desc.circles.push_back(circle);
  }
  if (r.has("point")) {
    ++kinds;
    // A point obstacle is a thin post: with radius 0 no range sensor could ever see it.
    desc.circles.push_back(
        {read_point(file, r.get("point"), r.path_of("point")), kPointPostRadius});
  }
  if (r.has("polygon")) {
    ++kinds;
    const YAML::Node n = r.get("polygon");
    if (n.IsSequence() && n.size() > kMaxPolygonPoints)
      fail(file, n, r.path_of("polygon"),
           fmt::format("a polygon has at most {} points, got {}", kMaxPolygonPoints, n.size()));
    if (n.IsSequence() && (polygon_work += n.size() * n.size()) > kMaxPolygonWork)
      fail(file, n, r.path_of("polygon"),
           fmt::format("the polygons are too large in all: the sum of their points squared is "
                       "above {} (e.g. 100 polygons of 1000 points)",
                       kMaxPolygonWork));
    auto pts = read_points(file, n, r.path_of("polygon"));
    if (pts.size() < 3)
      fail(file, n, r.path_of("polygon"),
           fmt::format("a polygon needs at least 3 points, got {}", pts.size()));
    if (!is_simple(pts))
      fail(file, n, r.path_of("polygon"),
           "the polygon crosses itself or has repeated points (it must be simple)");
    desc.polygons.push_back(std::move(pts));
  }
  if (r.has("rectangle")) {
    ++kinds;
    MapReader c = r.sub("rectangle");
    const Vec2 center = read_point(file, c.require("center", "[x, y]"), c.path_of("center"));
    const YAML::Node size_node = c.require("size", "[width, height]");
    const Vec2 size = read_point(file, size_node, c.path_of("size"));
    if (size.x() <= 0.0 || size.y() <= 0.0)
      fail(file, size_node, c.path_of("size"), "both sides must be positive");
    double angle = 0.0;
    if (c.has("angle")) {
      const YAML::Node a = c.get("angle");
      angle = check_angle(file, a, c.path_of("angle"), read_double(file, a, c.path_of("angle")));
    }
    c.finish();
    desc.polygons.push_back(make_rectangle(center, size, angle));
  }
  if (kinds != 1) {
    r.finish();  // a misspelt shape is named as such
    fail(file, item, key, "an obstacle is exactly one of: circle, point, polygon, rectangle");
  }
  r.finish();
}

void read_sensors(const std::string& file, MapReader& r, RobotSpec& robot) {
  if (r.has("mounts") && r.has("lidar"))
    fail(file, r.node(), r.path_of("mounts"), "give either mounts or lidar, not both");
  if (r.has("lidar")) {
    MapReader l = r.sub("lidar");
    const YAML::Node beams_node = l.require("beams", "a whole number of beams");
    const auto beams = io_detail::read_int(file, beams_node, l.path_of("beams"));
    if (beams < 1 || beams > static_cast<std::int64_t>(kMaxSensorsPerRobot))
      fail(file, beams_node, l.path_of("beams"),
           fmt::format("must be between 1 and {}", kMaxSensorsPerRobot));
    const YAML::Node fov_node = l.require("fov", "the field of view, rad");
    const double fov = read_positive(file, fov_node, l.path_of("fov"));
    if (fov > 2.0 * kPi + 1e-9)
      fail(file, fov_node, l.path_of("fov"),
           fmt::format("{:.6g} is more than 2 pi: angles are in radians", fov));
    const double lo = read_double(file, l.require("min_range", "m"), l.path_of("min_range"));
    const double hi = read_positive(file, l.require("max_range", "m"), l.path_of("max_range"));
    Pose2 mount;
    if (l.has("mount")) mount = read_pose(file, l.get("mount"), l.path_of("mount"));
    l.finish();
    robot.sensors = make_lidar(static_cast<int>(beams), fov, lo, hi, mount);
  }
  if (r.has("mounts")) {
    const YAML::Node n = r.get("mounts");
    if (!n.IsSequence() || n.size() == 0)
      fail(file, n, r.path_of("mounts"), "expected a list of [x, y, theta] sensor poses");
    if (n.size() > kMaxSensorsPerRobot)
      fail(file, n, r.path_of("mounts"),
           fmt::format("at most {} sensors, got {}", kMaxSensorsPerRobot, n.size()));
    const RangeSensorSpec base = robot.sensors.empty() ? RangeSensorSpec{} : robot.sensors[0];
    robot.sensors.clear();
    for (std::size_t i = 0; i < n.size(); ++i) {
      RangeSensorSpec s = base;
      s.mount = read_pose(file, n[i], fmt::format("{}[{}]", r.path_of("mounts"), i));
      robot.sensors.push_back(s);
    }
  }
  // Applies to every sensor, after any replacement above.
  auto each = [&](const char* key, auto apply) {
    if (!r.has(key)) return;
    const YAML::Node n = r.get(key);
    const double v = read_double(file, n, r.path_of(key));
    if (v < 0.0) fail(file, n, r.path_of(key), "must not be negative");
    for (RangeSensorSpec& s : robot.sensors) apply(s, v);
  };
  each("min_range", [](RangeSensorSpec& s, double v) { s.min_range = v; });
  each("max_range", [](RangeSensorSpec& s, double v) { s.max_range = v; });
  each("cone_angle", [](RangeSensorSpec& s, double v) { s.cone_angle = v; });
  if (r.has("cone_angle")) {
    const YAML::Node n = r.get("cone_angle");
    check_angle(file, n, r.path_of("cone_angle"), read_double(file, n, r.path_of("cone_angle")));
  }
  if (r.has("cone_rays")) {
    const YAML::Node n = r.get("cone_rays");
    const auto v = io_detail::read_int(file, n, r.path_of("cone_rays"));
    if (v < 1 || v > 64) fail(file, n, r.path_of("cone_rays"), "must be between 1 and 64");
    for (RangeSensorSpec& s : robot.sensors) s.cone_rays = static_cast<int>(v);
  }
  if (r.has("noise")) {
    const YAML::Node n = r.get("noise");
    robot.sensor_noise = read_double(file, n, r.path_of("noise"));
    if (robot.sensor_noise < 0.0) fail(file, n, r.path_of("noise"), "must not be negative");
  }
  std::size_t rays = 0;
  for (const RangeSensorSpec& s : robot.sensors) rays += static_cast<std::size_t>(s.cone_rays);
  if (rays > kMaxRaysPerRobot)
    fail(
        file, r.node(), r.path_of("cone_rays"),
        fmt::format("{} sensors of {} rays each cast {} rays per step, more than the {} a robot "
                    "may cast",
                    robot.sensors.size(), robot.sensors.front().cone_rays, rays, kMaxRaysPerRobot));
  r.finish();
}

// The robot section: a preset, then overrides of any of its values.
void read_robot(const std::string& file, MapReader& r, RobotTask& s) {
  std::string preset = "quickbot";
  if (r.has("preset")) preset = io_detail::read_string(file, r.get("preset"), r.path_of("preset"));
  std::optional<RobotPreset> p = find_robot_preset(preset);
  if (!p) {
    std::string names;
    for (auto name : robot_preset_names()) names += (names.empty() ? "" : ", ") + std::string(name);
    fail(file, r.get("preset"), r.path_of("preset"),
         fmt::format("unknown preset {} (expected one of: {})", quote_input(preset), names));
  }
  s.robot = std::move(p->robot);
  s.robot.preset = preset;
  s.controller.params = p->navigation;
  s.start = read_pose(file, r.require("start", "[x, y, theta]"), r.path_of("start"));
  s.start.theta = wrap_angle(s.start.theta);
  auto positive = [&](const char* key, double& field) {
    if (r.has(key)) field = read_positive(file, r.get(key), r.path_of(key));
  };
  positive("radius", s.robot.body_radius);
  positive("wheel_radius", s.robot.drive.wheel_radius);
  positive("track_width", s.robot.drive.track_width);
  positive("max_wheel_speed", s.robot.drive.max_wheel_speed);
  positive("max_acceleration", s.robot.max_acceleration);
  positive("max_angular_acceleration", s.robot.max_angular_acceleration);
  if (r.has("min_wheel_speed")) {
    const YAML::Node n = r.get("min_wheel_speed");
    s.robot.drive.min_wheel_speed = read_double(file, n, r.path_of("min_wheel_speed"));
    if (s.robot.drive.min_wheel_speed < 0.0 ||
        s.robot.drive.min_wheel_speed >= s.robot.drive.max_wheel_speed)
      fail(file, n, r.path_of("min_wheel_speed"), "must be in [0, max_wheel_speed)");
  }
  if (r.has("footprint")) {
    const YAML::Node n = r.get("footprint");
    if (n.IsSequence() && n.size() > 16)
      fail(file, n, r.path_of("footprint"),
           fmt::format("a footprint has at most 16 points, got {}", n.size()));
    auto pts = read_points(file, n, r.path_of("footprint"));
    if (!pts.empty() && (pts.size() < 3 || !is_simple(pts)))
      fail(file, n, r.path_of("footprint"),
           "a footprint is a simple polygon of 3 to 16 points (or [] for the body disc)");
    s.robot.footprint = std::move(pts);
  }
  if (r.has("sensors")) {
    MapReader sr = r.sub("sensors");
    read_sensors(file, sr, s.robot);
  }
  r.finish();
}

void read_controller(const std::string& file, MapReader& r, ControllerConfig& c) {
  // A preset first: the section's other keys change it.
  if (r.has("preset")) {
    const YAML::Node n = r.get("preset");
    const std::string name = io_detail::read_string(file, n, r.path_of("preset"));
    if (!apply_controller_preset(name, c))
      fail(file, n, r.path_of("preset"),
           fmt::format("unknown controller preset {} (expected {})", quote_input(name),
                       fmt::join(controller_preset_names(), " or ")));
  }
  if (r.has("kind")) {
    const YAML::Node n = r.get("kind");
    const std::string kind = io_detail::read_string(file, n, r.path_of("kind"));
    if (!find_builtin_controller(kind)) {
      std::vector<std::string_view> names;
      for (const BuiltinController& b : builtin_controllers()) names.push_back(b.name);
      fail(file, n, r.path_of("kind"),
           fmt::format("unknown controller {}{} (expected {})", quote_input(kind),
                       io_detail::did_you_mean(kind, names), builtin_controller_choices()));
    }
    c.kind = kind;
  }
  visit_fields(c, r);
  r.finish();
}

// `goal: [x, y]` or `goals: [[x, y], ...]` in the map `m` (the top level or one robot).
// `goals_in_all` counts the goals of every robot so far, against kMaxGoalsInAll.
std::vector<Vec2> read_goals(const std::string& file, MapReader& m, std::size_t& goals_in_all) {
  const bool has_goal = m.has("goal"), has_goals = m.has("goals");
  if (has_goal && has_goals)
    fail(file, m.get("goals"), m.path_of("goals"), "give either goal or goals, not both");
  if (!has_goal && !has_goals) m.require("goal", "goal: [x, y], or goals: [[x, y], ...]");
  if (has_goal) {
    ++goals_in_all;
    return {read_point(file, m.get("goal"), m.path_of("goal"))};
  }
  const YAML::Node n = m.get("goals");
  if (n.IsSequence() && n.size() > kMaxGoalsPerRobot)
    fail(file, n, m.path_of("goals"),
         fmt::format("at most {} goals, got {}", kMaxGoalsPerRobot, n.size()));
  if (n.IsSequence() && (goals_in_all += n.size()) > kMaxGoalsInAll)
    fail(file, n, m.path_of("goals"),
         fmt::format("the robots have more than {} goals in all", kMaxGoalsInAll));
  std::vector<Vec2> goals = read_points(file, n, m.path_of("goals"));
  if (goals.empty()) fail(file, n, m.path_of("goals"), "needs at least one goal");
  return goals;
}

// `robots:`, a list of robot sections, each with its own goal(s), an optional name and an
// optional controller section on top of the shared one. Each entry is read as a layer over the
// shared `robot:` section (no merged copy of the shared section per robot: loading stays linear
// in the file).
void read_fleet(const std::string& file, const YAML::Node& root, MapReader& top, Scenario& s,
                std::size_t& goals_in_all) {
  for (const char* key : {"goal", "goals"})
    if (top.has(key))
      fail(file, top.get(key), key, "with robots, each robot has its own goal or goals");
  // `robot:` beside `robots:` holds what the robots share; each entry overrides it.
  std::optional<YAML::Node> shared_robot;
  if (top.has("robot")) {
    shared_robot = top.get("robot");
    if (!shared_robot->IsMap()) fail(file, *shared_robot, "robot", "expected a mapping of keys");
    const YAML::Node& shared = *shared_robot;
    for (const char* own : {"start", "goal", "goals", "name"})
      if (shared[own])
        fail(file, shared[own], fmt::format("robot.{}", own),
             "with robots, each robot gives its own (robots[i].start, .goal, .name)");
  }
  const YAML::Node list = top.get("robots");
  if (!list.IsSequence() || list.size() == 0)
    fail(file, list, "robots", "expected a list of robots (robots: [{start: [x, y, theta], ...}])");
  if (list.size() > kMaxRobots)
    fail(file, list, "robots", fmt::format("at most {} robots, got {}", kMaxRobots, list.size()));
  std::optional<YAML::Node> shared_controller;
  if (top.has("controller")) shared_controller = top.get("controller");
  s.robots.reserve(list.size());
  std::unordered_set<std::string> names;
  std::size_t rays_in_all = 0;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = fmt::format("robots[{}]", i);
    const YAML::Node entry = list[i];
    if (!entry.IsMap())
      fail(file, entry, path, "expected a robot section ({start: [x, y, theta], goal: [x, y]})");
    MapReader r(file, entry, path);
    if (shared_robot) r.add_layer(*shared_robot, "robot");
    RobotTask task;
    task.name = r.has("name") ? io_detail::read_string(file, r.get("name"), r.path_of("name"))
                              : fmt::format("robot{}", i);
    if (!names.insert(task.name).second)
      fail(file, entry, r.path_of("name"),
           fmt::format("{} names two robots", quote_input(task.name)));
    task.goals = read_goals(file, r, goals_in_all);
    std::optional<YAML::Node> own_controller;
    if (r.has("controller")) own_controller = r.get("controller");
    read_robot(file, r, task);  // the preset, then this robot's values
    for (const RangeSensorSpec& sensor : task.robot.sensors)
      rays_in_all += static_cast<std::size_t>(sensor.cone_rays);
    if (rays_in_all > kMaxRaysInAll)
      fail(file, entry, path,
           fmt::format("the robots up to this one cast more than {} rays per step in all",
                       kMaxRaysInAll));
    for (const auto& [node, key] : {std::pair{shared_controller, std::string("controller")},
                                    std::pair{own_controller, r.path_of("controller")}}) {
      if (!node) continue;
      MapReader c(file, *node, key);
      read_controller(file, c, task.controller);
    }
    s.robots.push_back(std::move(task));
  }
  s.robots_listed = true;
  (void)root;
}

/// The lower-case extension of a map path.
std::string map_format(const std::filesystem::path& map) {
  std::string ext = map.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void read_world(const std::string& file, MapReader& top, const std::filesystem::path& origin,
                Scenario& s, WorldDesc& desc) {
  MapReader w = top.sub("world");
  if (w.has("bounds")) {
    const YAML::Node n = w.get("bounds");
    const auto b = io_detail::read_numbers(file, n, "world.bounds", 4);
    if (!(b[2] > b[0] && b[3] > b[1]))
      fail(file, n, "world.bounds",
           "expected [xmin, ymin, xmax, ymax] with xmin < xmax, ymin < ymax");
    desc.bounds = Box2{Vec2(b[0], b[1]), Vec2(b[2], b[3])};
  }
  if (w.has("obstacles")) {
    const YAML::Node n = w.get("obstacles");
    if (!n.IsSequence()) fail(file, n, "world.obstacles", "expected a list of obstacles");
    if (n.size() > kMaxObstacles)
      fail(file, n, "world.obstacles",
           fmt::format("at most {} obstacles, got {}", kMaxObstacles, n.size()));
    std::size_t polygon_work = 0;
    for (std::size_t i = 0; i < n.size(); ++i)
      read_obstacle(file, n[i], fmt::format("world.obstacles[{}]", i), desc, polygon_work);
  }
  std::optional<std::filesystem::path> map;
  std::string format;
  YAML::Node map_node;
  if (w.has("map")) {
    map_node = w.get("map");
    map = io_detail::read_string(file, map_node, "world.map");
    if (map->empty()) fail(file, map_node, "world.map", "is empty (a path to a map file)");
    if (map->is_relative()) *map = origin.parent_path() / *map;
    format = map_format(*map);
  }
  // Keys that mean nothing for this world's map are errors, never silently ignored.
  const bool takes_cell_size = format == ".map" || format == ".pgm" || format == ".png";
  const bool takes_unknown =
      format == ".yaml" || format == ".yml" || format == ".pgm" || format == ".png";
  io_detail::MapOptions options;
  WorldMapSource source;
  if (w.has("cell_size")) {
    const YAML::Node n = w.get("cell_size");
    if (!takes_cell_size)
      fail(
          file, n, "world.cell_size",
          map ? fmt::format("does not apply to a {} map (only a MovingAI .map or a bare "
                            ".pgm/.png image takes a cell size; a ROS .yaml gives its own "
                            "resolution)",
                            format.empty() ? fmt::format("'{}'", map->filename().string()) : format)
              : std::string("does not apply without world.map (only a MovingAI .map or a bare "
                            ".pgm/.png image takes a cell size)"));
    options.cell_size = read_positive(file, n, "world.cell_size");
    source.cell_size = options.cell_size;
  }
  if (w.has("unknown")) {
    const YAML::Node n = w.get("unknown");
    if (!takes_unknown)
      fail(file, n, "world.unknown",
           "applies only to occupancy maps (a ROS .yaml, .pgm or .png), not to this world");
    const std::string v = io_detail::read_string(file, n, "world.unknown");
    if (v != "occupied" && v != "free")
      fail(file, n, "world.unknown",
           fmt::format("expected occupied or free, got {}", quote_input(v)));
    options.unknown_is_occupied = v == "occupied";
    source.unknown = v;
  }
  if (map) {
    const std::size_t circles = desc.circles.size(), polygons = desc.polygons.size();
    desc.grid = io_detail::load_world_map(
        *map, options, desc, file, io_detail::where_of(map_node, "world.map"), s.input_files);
    std::error_code ec;
    const auto absolute = std::filesystem::absolute(*map, ec);
    source.path = (ec ? *map : absolute).lexically_normal().string();
    source.circles = desc.circles.size() - circles;
    source.polygons = desc.polygons.size() - polygons;
    s.world_map = source;
  }
  w.finish();
}

Scenario read_scenario(const YAML::Node& root, const std::filesystem::path& origin) {
  const std::string file = origin.string();
  if (!root.IsDefined() || root.IsNull())
    throw InputError(file, "", "the file is empty (a scenario needs world, robot and goal)");
  MapReader top(file, root, "");
  // Every top-level key, so that a misspelling anywhere gets its "did you mean".
  for (const char* key : {"name", "world", "robot", "robots", "goal", "goals", "controller", "sim",
                          "people", "people_file", "random_people", "forklifts"})
    top.has(key);
  Scenario s;
  s.name = origin.stem().string();
  if (top.has("name")) {
    const YAML::Node n = top.get("name");
    s.name = io_detail::read_string(file, n, "name");
    if (s.name.empty()) fail(file, n, "name", "is empty");
  }

  // robot first: its preset supplies the controller defaults.
  std::size_t goals_in_all = 0;
  const bool fleet = top.has("robots");
  if (fleet) {
    read_fleet(file, root, top, s, goals_in_all);
  } else {
    top.require("robot", "a section robot: {start: [x, y, theta]}");
    MapReader r = top.sub("robot");
    s.robots.emplace_back();
    read_robot(file, r, s.robots.back());
  }
  if (top.has("controller") && !fleet) {
    MapReader r = top.sub("controller");
    read_controller(file, r, s.robot().controller);
  }
  if (top.has("sim")) {
    MapReader r = top.sub("sim");
    visit_fields(s.sim, r);
    r.finish();
  }

  if (!fleet) s.robot().goals = read_goals(file, top, goals_in_all);

  WorldDesc desc;
  top.require("world", "a section world: {bounds: [xmin, ymin, xmax, ymax]}");
  read_world(file, top, origin, s, desc);
  io_detail::read_crowd(file, top, origin, s.crowd, s.input_files);
  const std::optional<RandomPeopleSpec> random_people = io_detail::read_random_people(file, top);
  top.finish();
  // Every robot is checked against every person and forklift every step (contacts, gaps), and
  // keeps a byte per pair: bounded before anything is made for them.
  const std::size_t movers = s.crowd.people.size() + s.crowd.forklifts.size();
  if (movers > 0 && s.robots.size() * movers > kMaxRobotMoverPairs)
    fail(file, root, "people",
         fmt::format("{} robots among {} people and forklifts make {} robot-mover pairs, more "
                     "than the {} a scenario may have (each pair is checked every step)",
                     s.robots.size(), movers, s.robots.size() * movers, kMaxRobotMoverPairs));
  s.world = std::make_shared<const World>(std::move(desc));
  if (random_people) io_detail::add_random_people(file, root, *random_people, s);
  validate_scenario(s, file);
  return s;
}

/// The dotted key an error names: "line 3: sim.dt" -> "sim.dt", "sim.dt" -> "sim.dt",
/// "line 3" -> "".
std::string error_key(const std::string& where) {
  if (where.rfind("line ", 0) != 0) return where;
  const auto colon = where.find(": ");
  return colon == std::string::npos ? std::string() : where.substr(colon + 2);
}

/// An error about a key that an override set (or a key inside it, or one of its parents that
/// the override created), blamed on that override: the scenario file's line numbers mean nothing
/// for it. nullopt for errors about the file's own keys or another file.
std::optional<InputError> blame_override(const InputError& e, const std::string& file,
                                         std::span<const ScenarioOverride> overrides) {
  if (e.file != file) return std::nullopt;
  std::string key = error_key(e.where);
  // "controller.d_o (robots[2])": the key before the robot it is about.
  if (const auto paren = key.find(" ("); paren != std::string::npos) key.erase(paren);
  if (key.empty()) return std::nullopt;
  const auto under = [](const std::string& a, const std::string& b) {  // a is below b
    return a.size() > b.size() && a.compare(0, b.size(), b) == 0 &&
           (a[b.size()] == '.' || a[b.size()] == '[');
  };
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it) {  // the last one wins
    const std::string set_key = it->assignment.substr(0, it->assignment.find('='));
    const bool below = under(key, set_key);
    // An error about a parent of the key, at a place the file does not have (the override made
    // it), or naming a key the override misspelt ("controler" for --set controler.kind=...).
    const bool above = under(set_key, key) && error_key(e.where) == e.where;
    if (key != set_key && !below && !above) continue;
    return InputError(it->file, it->where + (below ? ": " + key : std::string()), e.detail);
  }
  return std::nullopt;
}

}  // namespace

std::vector<ScenarioOverride> user_overrides(std::span<const std::string> sets) {
  std::vector<ScenarioOverride> out;
  out.reserve(sets.size());
  for (const std::string& s : sets) out.push_back({s, "", "--set " + s});
  return out;
}

Scenario load_scenario_text_with_overrides(std::string_view yaml,
                                           const std::filesystem::path& origin,
                                           std::span<const ScenarioOverride> overrides) {
  const std::string file = origin.string();
  // Names and paths go to JSON outputs: the file's name and its text are UTF-8 or refused.
  io_detail::check_utf8_path(origin, file, "");
  io_detail::check_utf8_text(yaml, file);
  YAML::Node root = parse_yaml(std::string(yaml), file, "");
  if (root.IsDefined() && !root.IsNull() && !root.IsMap())
    throw InputError(file, "line 1", "a scenario is a mapping of sections (world, robot, goal)");
  if (!root.IsDefined() || root.IsNull())
    throw InputError(file, "", "the file is empty (a scenario needs world, robot and goal)");
  std::vector<YAML::Node> keep{root};  // every handle the tree's nodes live in (apply_override)
  if (!overrides.empty()) {
    root.reset(shallow_copy(root));  // overrides change copies, never a node the file aliases
    keep.push_back(root);
    for (const ScenarioOverride& o : overrides) apply_override(root, o, keep);
  }
  try {
    return read_scenario(root, origin);
  } catch (const YAML::Exception& e) {
    throw InputError(file, fmt::format("line {}", e.mark.line + 1), e.msg);
  } catch (const InputError& e) {
    if (auto blamed = blame_override(e, file, overrides)) throw std::move(*blamed);
    throw;
  }
}

Scenario load_scenario_text(std::string_view yaml, const std::filesystem::path& origin,
                            std::span<const std::string> overrides) {
  return load_scenario_text_with_overrides(yaml, origin, user_overrides(overrides));
}

Scenario load_scenario_with_overrides(const std::filesystem::path& path,
                                      std::span<const ScenarioOverride> overrides) {
  const std::string text =
      io_detail::read_input_file(path, "scenario", io_detail::kMaxScenarioBytes);
  if (text.find('\0') != std::string::npos)
    throw InputError(path.string(), "", "binary data, not a YAML scenario");
  Scenario s = load_scenario_text_with_overrides(text, path, overrides);
  s.input_files.insert(s.input_files.begin(), path.string());
  return s;
}

Scenario load_scenario_file(const std::filesystem::path& path,
                            std::span<const std::string> overrides) {
  return load_scenario_with_overrides(path, user_overrides(overrides));
}

}  // namespace floornav
