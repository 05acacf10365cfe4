#include "floornav/io/scenario_file.hpp"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <unordered_set>

#include "crowd_file.hpp"
#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/nav/dwa_controller.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/validate.hpp"
#include "world_map.hpp"
#include "yaml_reader.hpp"

namespace floornav {

using io_detail::fail;
using io_detail::MapReader;
using io_detail::read_double;
using io_detail::read_point;
using io_detail::read_points;

namespace {

constexpr std::size_t kMaxScenarioBytes = 16u << 20;  // a scenario is text, not data
constexpr std::size_t kMaxObstacles = 1000000;
constexpr double kPointPostRadius = 0.03;  // m, the radius given to `point:` obstacles
// The simplicity check is quadratic in a polygon's points: bound them, per polygon and in all
// (YAML aliases can repeat one polygon a million times in a small file), so that no file can
// make it hang. The same goes for goals and sensor mounts, each checked or simulated in turn.
constexpr std::size_t kMaxPolygonPoints = 1000;
constexpr std::size_t kMaxPolygonPointsInAll = 100000;
constexpr std::size_t kMaxGoals = 10000;
// A fleet scenario lists at most this many robots (each has its own goals and sensors).
constexpr std::size_t kMaxRobots = 100000;
constexpr std::size_t kMaxMounts = 100000;

/// YAML text -> tree; errors name `file` (or the --set value when `file` is empty).
YAML::Node parse_yaml(const std::string& text, const std::string& file, const std::string& where) {
  try {
    return YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    throw InputError(file, where.empty() ? fmt::format("line {}", e.mark.line + 1) : where,
                     "not valid YAML: the text nests too deeply");
  } catch (const YAML::ParserException& e) {
    throw InputError(file, where.empty() ? fmt::format("line {}", e.mark.line + 1) : where,
                     "not valid YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(file, where, std::string("not valid YAML: ") + e.what());
  }
}

// --- --set overrides ------------------------------------------------------------------------

void apply_override(YAML::Node& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("", "--set " + assignment, "expected KEY=VALUE");
  const std::string key = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  YAML::Node value;
  try {
    value = parse_yaml(text, "", "--set " + key);
  } catch (const InputError& e) {
    throw InputError("", "--set " + key, fmt::format("cannot read value '{}': {}", text, e.detail));
  }
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) {
    if (part.empty()) throw InputError("", "--set " + key, "empty part in the key path");
    parts.push_back(part);
  }
  // Walk down with plain node copies (yaml-cpp nodes are handles), creating maps as needed. A part
  // may index a list, as errors name its entries: `robots[2].start`. (Assigning one yaml-cpp
  // node to another copies content, so the walk keeps each step's handle in `chain`.)
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i < parts.size(); ++i) {
    YAML::Node node = chain.back();
    std::string name = parts[i];
    std::vector<std::size_t> indices;
    while (!name.empty() && name.back() == ']') {
      const auto open = name.rfind('[');
      std::size_t index = 0;
      const std::string digits =
          open == std::string::npos ? "" : name.substr(open + 1, name.size() - open - 2);
      const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
      if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size())
        throw InputError("", "--set " + key,
                         fmt::format("'{}': a list index is a number in brackets", parts[i]));
      indices.insert(indices.begin(), index);
      name.erase(open);
    }
    if (name.empty()) throw InputError("", "--set " + key, "empty part in the key path");
    if (!node.IsMap() && !node.IsNull())
      throw InputError("", "--set " + key,
                       fmt::format("'{}' is not a mapping, cannot set a key inside it",
                                   i > 0 ? parts[i - 1] : std::string("the scenario")));
    const bool last = i + 1 == parts.size();
    if (last && indices.empty()) {
      // `goal` and `goals` are alternatives: setting one replaces the other.
      if ((name == "goal" || name == "goals") && node.IsMap())
        node.remove(name == "goal" ? "goals" : "goal");
      node[name] = value;
      return;
    }
    YAML::Node child = node[name];
    if (indices.empty() && (!child.IsDefined() || child.IsNull())) {
      node[name] = YAML::Node(YAML::NodeType::Map);
      child = node[name];
    }
    chain.push_back(child);
    std::string path = name;
    for (std::size_t k = 0; k < indices.size(); ++k) {
      YAML::Node list = chain.back();
      if (!list.IsSequence() || indices[k] >= list.size())
        throw InputError(
            "", "--set " + key,
            fmt::format("'{}' has no entry [{}] ({})", path, indices[k],
                        list.IsSequence() ? fmt::format("it has {}", list.size()) : "not a list"));
      if (last && k + 1 == indices.size()) {
        list[indices[k]] = value;
        return;
      }
      path += fmt::format("[{}]", indices[k]);
      chain.push_back(list[indices[k]]);
    }
  }
}

// --- sections -------------------------------------------------------------------------------

Pose2 read_pose(const std::string& file, const YAML::Node& n, const std::string& key) {
  const auto v = io_detail::read_numbers(file, n, key, 3);
  return {Vec2(v[0], v[1]), v[2]};
}

double read_positive(const std::string& file, const YAML::Node& n, const std::string& key) {
  const double v = read_double(file, n, key);
  if (v <= 0.0) fail(file, n, key, fmt::format("must be positive, got {}", v));
  return v;
}

void read_obstacle(const std::string& file, const YAML::Node& item, const std::string& key,
                   WorldDesc& desc, std::size_t& polygon_points) {
  MapReader r(file, item, key);
  int kinds = 0;
  if (r.has("circle")) {
    ++kinds;
    MapReader c(file, r.get("circle"), r.path_of("circle"));
    Circle circle;
    circle.center = read_point(file, c.get("center"), c.path_of("center"));
    circle.radius = read_positive(file, c.get("radius"), c.path_of("radius"));
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
    if (n.IsSequence() && (polygon_points += n.size()) > kMaxPolygonPointsInAll)
      fail(file, n, r.path_of("polygon"),
           fmt::format("the polygons have more than {} points in all", kMaxPolygonPointsInAll));
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
    MapReader c(file, r.get("rectangle"), r.path_of("rectangle"));
    const Vec2 center = read_point(file, c.get("center"), c.path_of("center"));
    const Vec2 size = read_point(file, c.get("size"), c.path_of("size"));
    if (size.x() <= 0.0 || size.y() <= 0.0)
      fail(file, c.node()["size"], c.path_of("size"), "both sides must be positive");
    double angle = 0.0;
    if (c.has("angle")) angle = read_double(file, c.get("angle"), c.path_of("angle"));
    c.finish();
    desc.polygons.push_back(make_rectangle(center, size, angle));
  }
  if (kinds != 1)
    fail(file, item, key, "an obstacle is exactly one of: circle, point, polygon, rectangle");
  r.finish();
}

void read_sensors(const std::string& file, MapReader& r, RobotSpec& robot) {
  if (r.has("mounts") && r.has("lidar"))
    fail(file, r.node(), r.path_of("mounts"), "give either mounts or lidar, not both");
  if (r.has("lidar")) {
    MapReader l(file, r.get("lidar"), r.path_of("lidar"));
    const auto beams = io_detail::read_int(file, l.get("beams"), l.path_of("beams"));
    if (beams < 1 || beams > 100000)
      fail(file, l.node()["beams"], l.path_of("beams"), "must be between 1 and 100000");
    const double fov = read_positive(file, l.get("fov"), l.path_of("fov"));
    if (fov > 2.0 * kPi + 1e-9) fail(file, l.node()["fov"], l.path_of("fov"), "at most 2 pi");
    const double lo = read_double(file, l.get("min_range"), l.path_of("min_range"));
    const double hi = read_positive(file, l.get("max_range"), l.path_of("max_range"));
    Pose2 mount;
    if (l.has("mount")) mount = read_pose(file, l.get("mount"), l.path_of("mount"));
    l.finish();
    robot.sensors = make_lidar(static_cast<int>(beams), fov, lo, hi, mount);
  }
  if (r.has("mounts")) {
    const YAML::Node n = r.get("mounts");
    if (!n.IsSequence() || n.size() == 0)
      fail(file, n, r.path_of("mounts"), "expected a list of [x, y, theta] sensor poses");
    if (n.size() > kMaxMounts)
      fail(file, n, r.path_of("mounts"),
           fmt::format("at most {} sensors, got {}", kMaxMounts, n.size()));
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
  r.finish();
}

// The robot section: a preset, then overrides of any of its values.
void read_robot(const std::string& file, MapReader& r, RobotTask& s) {
  std::string preset = "quickbot";
  if (r.has("preset")) {
    const YAML::Node n = r.get("preset");
    preset = io_detail::read_string(file, n, r.path_of("preset"));
    if (!find_robot_preset(preset)) {
      std::string names;
      for (auto name : robot_preset_names())
        names += (names.empty() ? "" : ", ") + std::string(name);
      fail(file, n, r.path_of("preset"),
           fmt::format("unknown preset '{}' (expected one of: {})", preset, names));
    }
  }
  const RobotPreset p = *find_robot_preset(preset);
  s.robot = p.robot;
  s.robot.preset = preset;
  s.controller.params = p.navigation;
  if (!r.has("start")) fail(file, r.node(), r.path_of("start"), "missing (x, y, theta)");
  s.start = read_pose(file, r.get("start"), r.path_of("start"));
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
    auto pts = read_points(file, n, r.path_of("footprint"));
    if (!pts.empty() && (pts.size() < 3 || pts.size() > 16 || !is_simple(pts)))
      fail(file, n, r.path_of("footprint"),
           "a footprint is a simple polygon of 3 to 16 points (or [] for the body disc)");
    s.robot.footprint = std::move(pts);
  }
  if (r.has("sensors")) {
    MapReader sr(file, r.get("sensors"), r.path_of("sensors"));
    read_sensors(file, sr, s.robot);
  }
  r.finish();
}

void read_controller(const std::string& file, MapReader& r, ControllerConfig& c) {
  if (r.has("kind")) {
    const YAML::Node n = r.get("kind");
    const std::string kind = io_detail::read_string(file, n, r.path_of("kind"));
    const auto k = parse_controller_kind(kind);
    if (!k && kind != kDwaKindName)
      fail(file, n, r.path_of("kind"),
           fmt::format("unknown controller '{}' (expected hybrid, hard_switch, blended, "
                       "go_to_goal or dwa)",
                       kind));
    c.kind = kind;
  }
  if (r.has("robot_avoidance")) {
    const YAML::Node n = r.get("robot_avoidance");
    const std::string name = io_detail::read_string(file, n, r.path_of("robot_avoidance"));
    const auto a = parse_robot_avoidance(name);
    if (!a)
      fail(file, n, r.path_of("robot_avoidance"),
           fmt::format("unknown robot avoidance '{}' (expected none or orca)", name));
    c.params.robot_avoidance = *a;
  }
  c.params.serialize(r);
  r.finish();
}

// `goal: [x, y]` or `goals: [[x, y], ...]` in the map `m` (the top level or one robot).
std::vector<Vec2> read_goals(const std::string& file, MapReader& m) {
  const bool has_goal = m.has("goal"), has_goals = m.has("goals");
  if (has_goal == has_goals)
    fail(file, m.node(), m.path_of(has_goal ? "goals" : "goal"),
         has_goal ? "give either goal or goals, not both" : "missing (goal: [x, y])");
  if (has_goal) return {read_point(file, m.get("goal"), m.path_of("goal"))};
  const YAML::Node n = m.get("goals");
  if (n.IsSequence() && n.size() > kMaxGoals)
    fail(file, n, m.path_of("goals"), fmt::format("at most {} goals, got {}", kMaxGoals, n.size()));
  std::vector<Vec2> goals = read_points(file, n, m.path_of("goals"));
  if (goals.empty()) fail(file, n, m.path_of("goals"), "needs at least one goal");
  return goals;
}

// `entry` over `defaults`: keys of `entry` win; maps found in both (sensors, sensors.lidar) are
// merged the same way. Nodes keep their marks, so errors still name the right line.
YAML::Node with_defaults(const YAML::Node& entry, const YAML::Node& defaults) {
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& kv : defaults) out[kv.first.as<std::string>()] = kv.second;
  for (const auto& kv : entry) {
    const std::string key = kv.first.as<std::string>();
    const YAML::Node d = defaults[key];
    out[key] = d && d.IsMap() && kv.second.IsMap() ? with_defaults(kv.second, d) : kv.second;
  }
  return out;
}

// `robots:`, a list of robot sections, each with its own goal(s), an optional name and an
// optional controller section on top of the shared one.
void read_fleet(const std::string& file, const YAML::Node& root, MapReader& top, Scenario& s) {
  for (const char* key : {"goal", "goals"})
    if (top.has(key)) fail(file, root, key, "with robots, each robot has its own goal or goals");
  // `robot:` beside `robots:` holds what the robots share; each entry overrides it.
  std::optional<YAML::Node> shared_robot;
  if (top.has("robot")) {
    shared_robot = top.get("robot");
    if (!shared_robot->IsMap()) fail(file, *shared_robot, "robot", "expected a mapping of keys");
    for (const char* own : {"start", "goal", "goals", "name"})
      if ((*shared_robot)[own])
        fail(file, (*shared_robot)[own], fmt::format("robot.{}", own),
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
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = fmt::format("robots[{}]", i);
    if (!list[i].IsMap())
      fail(file, list[i], path, "expected a robot section ({start: [x, y, theta], goal: [x, y]})");
    MapReader r(file, shared_robot ? with_defaults(list[i], *shared_robot) : list[i], path);
    RobotTask task;
    task.name = r.has("name") ? io_detail::read_string(file, r.get("name"), r.path_of("name"))
                              : fmt::format("robot{}", i);
    if (!names.insert(task.name).second)
      fail(file, list[i], r.path_of("name"), fmt::format("'{}' names two robots", task.name));
    task.goals = read_goals(file, r);
    std::optional<YAML::Node> own_controller;
    if (r.has("controller")) own_controller = r.get("controller");
    read_robot(file, r, task);  // the preset, then this robot's values
    for (const auto& [node, key] : {std::pair{shared_controller, std::string("controller")},
                                    std::pair{own_controller, r.path_of("controller")}}) {
      if (!node) continue;
      MapReader c(file, *node, key);
      read_controller(file, c, task.controller);
    }
    s.robots.push_back(std::move(task));
  }
  s.robots_listed = true;
}

Scenario read_scenario(const YAML::Node& root, const std::filesystem::path& origin) {
  const std::string file = origin.string();
  if (!root.IsDefined() || root.IsNull())
    throw InputError(file, "", "the file is empty (a scenario needs world, robot and goal)");
  MapReader top(file, root, "");
  Scenario s;
  s.name = origin.stem().string();
  if (top.has("name")) s.name = io_detail::read_string(file, top.get("name"), "name");

  // robot first: its preset supplies the controller defaults.
  const bool fleet = top.has("robots");
  if (fleet) {
    read_fleet(file, root, top, s);
  } else {
    if (!top.has("robot"))
      fail(file, root, "robot", "missing section (robot: {start: [x, y, theta]})");
    MapReader r(file, top.get("robot"), "robot");
    s.robots.emplace_back();
    read_robot(file, r, s.robots.back());
  }
  if (top.has("controller") && !fleet) {
    MapReader r(file, top.get("controller"), "controller");
    read_controller(file, r, s.robot().controller);
  }
  if (top.has("sim")) {
    MapReader r(file, top.get("sim"), "sim");
    s.sim.serialize(r);
    r.finish();
  }

  if (!fleet) s.robot().goals = read_goals(file, top);

  WorldDesc desc;
  if (!top.has("world")) fail(file, root, "world", "missing section (world: {bounds: [...]})");
  {
    MapReader w(file, top.get("world"), "world");
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
      if (n.size() > kMaxObstacles) fail(file, n, "world.obstacles", "too many obstacles");
      std::size_t polygon_points = 0;
      for (std::size_t i = 0; i < n.size(); ++i)
        read_obstacle(file, n[i], fmt::format("world.obstacles[{}]", i), desc, polygon_points);
    }
    io_detail::MapOptions options;
    if (w.has("cell_size"))
      options.cell_size = read_positive(file, w.get("cell_size"), "world.cell_size");
    if (w.has("unknown")) {
      const YAML::Node n = w.get("unknown");
      const std::string v = io_detail::read_string(file, n, "world.unknown");
      if (v != "occupied" && v != "free")
        fail(file, n, "world.unknown", fmt::format("expected occupied or free, got '{}'", v));
      options.unknown_is_occupied = v == "occupied";
    }
    if (w.has("map")) {
      const YAML::Node n = w.get("map");
      std::filesystem::path map = io_detail::read_string(file, n, "world.map");
      if (map.is_relative()) map = origin.parent_path() / map;
      desc.grid =
          io_detail::load_world_map(map, options, desc, file, io_detail::where_of(n, "world.map"));
    }
    w.finish();
  }
  io_detail::read_crowd(file, top, origin, s.crowd);
  top.finish();
  s.world = std::make_shared<const World>(std::move(desc));
  validate_scenario(s, file);
  return s;
}

}  // namespace

namespace {

/// An error about a key that a --set replaced, blamed on that --set: the file's line numbers
/// mean nothing for it. nullopt for errors about the file's own keys or another file.
std::optional<InputError> blame_override(const InputError& e, const std::string& file,
                                         std::span<const std::string> overrides) {
  if (e.file != file) return std::nullopt;
  std::string key = e.where;  // "line 3: sim.dt", "sim.dt" or "line 3"
  if (key.rfind("line ", 0) == 0) {
    const auto colon = key.find(": ");
    key = colon == std::string::npos ? std::string() : key.substr(colon + 2);
  }
  if (key.empty()) return std::nullopt;
  for (auto it = overrides.rbegin(); it != overrides.rend(); ++it) {  // the last --set wins
    const std::string set_key = it->substr(0, it->find('='));
    const bool below = key.size() > set_key.size() &&
                       key.compare(0, set_key.size(), set_key) == 0 &&
                       (key[set_key.size()] == '.' || key[set_key.size()] == '[');
    if (key != set_key && !below) continue;
    return InputError(file, "--set " + *it + (below ? ": " + key : std::string()), e.detail);
  }
  return std::nullopt;
}

}  // namespace

Scenario load_scenario_text(std::string_view yaml, const std::filesystem::path& origin,
                            std::span<const std::string> overrides) {
  const std::string file = origin.string();
  YAML::Node root = parse_yaml(std::string(yaml), file, "");
  if (root.IsDefined() && !root.IsNull() && !root.IsMap())
    throw InputError(file, "line 1", "a scenario is a mapping of sections (world, robot, goal)");
  if (!root.IsDefined() || root.IsNull())
    throw InputError(file, "", "the file is empty (a scenario needs world, robot and goal)");
  for (const std::string& o : overrides) apply_override(root, o);
  try {
    return read_scenario(root, origin);
  } catch (const YAML::Exception& e) {
    throw InputError(file, fmt::format("line {}", e.mark.line + 1), e.msg);
  } catch (const InputError& e) {
    if (auto blamed = blame_override(e, file, overrides)) throw std::move(*blamed);
    throw;
  }
}

Scenario load_scenario_file(const std::filesystem::path& path,
                            std::span<const std::string> overrides) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path.string(), "",
                     std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path.string(), "", "cannot read: " + ec.message());
  if (size > kMaxScenarioBytes)
    throw InputError(path.string(), "", fmt::format("{} bytes is too large for a scenario", size));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "", "cannot open for reading");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.find('\0') != std::string::npos)
    throw InputError(path.string(), "", "binary data, not a YAML scenario");
  return load_scenario_text(text, path, overrides);
}

}  // namespace floornav
