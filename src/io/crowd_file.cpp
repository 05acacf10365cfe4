#include "crowd_file.hpp"

#include <fmt/format.h>

#include <yaml-cpp/depthguard.h>

#include <array>
#include <initializer_list>
#include <set>

#include "input_file.hpp"
#include "utf8_input.hpp"

namespace floornav::io_detail {

namespace {

// A scenario names at most this many people and forklifts (each is simulated every step), and a
// person or route at most this many points.
constexpr std::size_t kMaxMovers = 10000;
constexpr std::size_t kMaxRoutePoints = 1000;
constexpr std::size_t kMaxAgentFileBytes = 4u << 20;
// All goals of all people of a file (YAML aliases can repeat a goal list without repeating text).
constexpr std::size_t kMaxWaypointsInAll = 1000000;

double read_positive(const std::string& file, MapReader& r, const char* key, double fallback) {
  if (!r.has(key)) return fallback;
  const YAML::Node n = r.get(key);
  const double v = read_double(file, n, r.path_of(key));
  if (!(v > 0.0)) fail(file, n, r.path_of(key), fmt::format("must be positive, got {}", v));
  return v;
}

std::vector<Vec2> read_route(const std::string& file, MapReader& r, const char* key,
                             std::size_t at_least) {
  if (!r.has(key))
    fail(file, r.node(), r.path_of(key),
         fmt::format("missing (a list of [x, y], at least {})", at_least));
  const YAML::Node n = r.get(key);
  if (n.IsSequence() && n.size() > kMaxRoutePoints)
    fail(file, n, r.path_of(key), fmt::format("at most {} points", kMaxRoutePoints));
  std::vector<Vec2> pts = read_points(file, n, r.path_of(key));
  if (pts.size() < at_least)
    fail(file, n, r.path_of(key), fmt::format("needs at least {} points", at_least));
  return pts;
}

YAML::Node checked_list(const std::string& file, const YAML::Node& n, const std::string& key) {
  if (!n.IsSequence()) fail(file, n, key, "expected a list");
  if (n.size() > kMaxMovers) fail(file, n, key, fmt::format("at most {} entries", kMaxMovers));
  return n;
}

PersonSpec read_person(const std::string& file, const YAML::Node& item, const std::string& key,
                       std::size_t index) {
  MapReader r(file, item, key);
  PersonSpec p;
  p.name = r.has("name") ? read_string(file, r.get("name"), r.path_of("name"))
                         : fmt::format("person{}", index);
  if (!r.has("start")) fail(file, item, r.path_of("start"), "missing ([x, y])");
  p.start = read_point(file, r.get("start"), r.path_of("start"));
  p.waypoints = read_route(file, r, "waypoints", 1);
  p.speed = read_positive(file, r, "speed", p.speed);
  p.radius = read_positive(file, r, "radius", p.radius);
  p.goal_radius = read_positive(file, r, "goal_radius", p.goal_radius);
  if (r.has("cyclic")) p.cyclic = read_bool(file, r.get("cyclic"), r.path_of("cyclic"));
  r.finish();
  return p;
}

ForkliftSpec read_forklift(const std::string& file, const YAML::Node& item, const std::string& key,
                           std::size_t index) {
  MapReader r(file, item, key);
  ForkliftSpec f;
  f.name = r.has("name") ? read_string(file, r.get("name"), r.path_of("name"))
                         : fmt::format("forklift{}", index);
  f.route = read_route(file, r, "route", 2);
  f.speed = read_positive(file, r, "speed", f.speed);
  if (r.has("size")) {
    const YAML::Node n = r.get("size");
    f.size = read_point(file, n, r.path_of("size"));
    if (!(f.size.x() > 0.0 && f.size.y() > 0.0))
      fail(file, n, r.path_of("size"), "both sides must be positive ([length, width])");
  }
  if (r.has("stop_distance")) {
    const YAML::Node n = r.get("stop_distance");
    f.stop_distance = read_double(file, n, r.path_of("stop_distance"));
    if (f.stop_distance < 0.0) fail(file, n, r.path_of("stop_distance"), "must not be negative");
  }
  if (r.has("cyclic")) f.cyclic = read_bool(file, r.get("cyclic"), r.path_of("cyclic"));
  for (std::size_t k = 0; k < f.route.size(); ++k)
    if ((f.route[(k + 1) % f.route.size()] - f.route[k]).norm() <= 0.0 &&
        (k + 1 < f.route.size() || f.cyclic))
      fail(file, r.node()["route"], r.path_of("route"),
           fmt::format("points {} and {} are the same: a route needs distinct consecutive points",
                       k, (k + 1) % f.route.size()));
  r.finish();
  return f;
}

// The keys of a HuNavSim file that floornav reads or knowingly leaves out (HuNavSim's behaviour
// models, its ids and skins: every agent walks by the social force model here). Any other key is
// refused as unknown, as a scenario's are: a misspelt `max_vell` is never a silent default.
constexpr std::array kIgnoredAgentKeys = {"id", "skin", "group_id", "behavior"};
constexpr std::array kBehaviourKeys = {"type",
                                       "configuration",
                                       "duration",
                                       "once",
                                       "vel",
                                       "dist",
                                       "goal_force_factor",
                                       "obstacle_force_factor",
                                       "social_force_factor",
                                       "other_force_factor"};

Vec2 read_xy(const std::string& file, MapReader& r, std::initializer_list<const char*> ignored) {
  for (const char* key : ignored) r.has(key);  // HuNavSim's height and heading: not used
  const double x = read_double(file, r.require("x", "m"), r.path_of("x"));  // x, then y
  const double y = read_double(file, r.require("y", "m"), r.path_of("y"));
  const Vec2 p(x, y);
  r.finish();
  return p;
}

double read_agent_positive(const std::string& file, MapReader& r, const char* key,
                           double fallback) {
  if (!r.has(key)) return fallback;
  const YAML::Node n = r.get(key);
  const double v = read_double(file, n, r.path_of(key));
  if (!(v > 0.0)) fail(file, n, r.path_of(key), "must be positive");
  return v;
}

PersonSpec read_agent(const std::string& file, MapReader& params, const std::string& name,
                      std::size_t& waypoints_in_all) {
  MapReader a = params.sub(name);
  for (const char* key : kIgnoredAgentKeys) a.has(key);
  if (a.has("behavior")) {
    MapReader b = a.sub("behavior");
    for (const char* key : kBehaviourKeys) b.has(key);
    b.finish();
  }
  PersonSpec p;
  p.name = name;
  {
    MapReader pose = a.sub("init_pose");
    p.start = read_xy(file, pose, {"z", "h"});
  }
  p.speed = read_agent_positive(file, a, "max_vel", p.speed);
  p.radius = read_agent_positive(file, a, "radius", p.radius);
  p.goal_radius = read_agent_positive(file, a, "goal_radius", p.goal_radius);
  if (a.has("cyclic_goals"))
    p.cyclic = read_bool(file, a.get("cyclic_goals"), a.path_of("cyclic_goals"));
  const YAML::Node goals = a.require("goals", "a list of goal names");
  const std::string goals_key = a.path_of("goals");
  if (!goals.IsSequence()) fail(file, goals, goals_key, "expected a list of goal names");
  if (goals.size() == 0) fail(file, goals, goals_key, "needs at least one goal");
  if (goals.size() > kMaxRoutePoints)
    fail(file, goals, goals_key,
         fmt::format("at most {} goals per agent, got {}", kMaxRoutePoints, goals.size()));
  if ((waypoints_in_all += goals.size()) > kMaxWaypointsInAll)
    fail(
        file, goals, goals_key,
        fmt::format("the people have more than {} goals and waypoints in all", kMaxWaypointsInAll));
  for (std::size_t k = 0; k < goals.size(); ++k) {
    const std::string key = fmt::format("{}[{}]", goals_key, k);
    const std::string g = read_string(file, goals[k], key);
    if (!a.has(g)) fail(file, goals[k], key, fmt::format("no goal '{}' in {}", g, name));
    MapReader goal = a.sub(g);
    p.waypoints.push_back(read_xy(file, goal, {"z", "h"}));
  }
  a.finish();
  return p;
}

}  // namespace

std::vector<PersonSpec> load_hunav_agents(const std::filesystem::path& path) {
  const std::string file = path.string();
  // Named for what it is (missing, unreadable, a folder, a FIFO, a device, too large).
  const std::string text = read_input_file(path, "HuNavSim agent", kMaxAgentFileBytes);
  if (text.find('\0') != std::string::npos)
    throw InputError(file, "", "binary data, not a HuNavSim agent file (YAML)");
  check_utf8_text(text, file);
  YAML::Node root;
  try {
    const OneDocument doc = load_one_document(text);
    if (doc.second)
      throw InputError(file, fmt::format("line {}", doc.second->line + 1),
                       "a second YAML document: an agent file is one document");
    root.reset(doc.node);
  } catch (const YAML::DeepRecursion& e) {
    throw InputError(file, fmt::format("line {}", e.mark.line + 1),
                     "not valid YAML: the text nests too deeply");
  } catch (const YAML::Exception& e) {
    throw InputError(file, fmt::format("line {}", e.mark.line + 1), "not valid YAML: " + e.msg);
  }
  if (!root.IsDefined() || root.IsNull())
    throw InputError(file, "", "the file is empty (expected hunav_loader: ros__parameters: ...)");
  MapReader top(file, root, "");
  MapReader loader = top.sub("hunav_loader");
  top.finish();
  MapReader params = loader.sub("ros__parameters");
  loader.finish();
  for (const char* key : {"map", "publish_people"}) params.has(key);  // for the ROS node only
  const YAML::Node names = params.require("agents", "a list of agent names");
  checked_list(file, names, params.path_of("agents"));
  std::vector<PersonSpec> people;
  std::size_t waypoints_in_all = 0;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string key = fmt::format("{}[{}]", params.path_of("agents"), i);
    const std::string name = read_string(file, names[i], key);
    if (!seen.insert(name).second)
      fail(file, names[i], key, fmt::format("{} is listed twice", quote_input(name)));
    if (!params.has(name))
      fail(file, names[i], key, fmt::format("no section {} for this agent", quote_input(name)));
    people.push_back(read_agent(file, params, name, waypoints_in_all));
  }
  params.finish();
  return people;
}

void read_crowd(const std::string& file, MapReader& top, const std::filesystem::path& origin,
                CrowdSpec& crowd, std::vector<std::string>& files_read) {
  if (top.has("people_file")) {
    const YAML::Node n = top.get("people_file");
    std::filesystem::path agents = read_string(file, n, "people_file");
    if (agents.empty()) fail(file, n, "people_file", "is empty (a path to a HuNavSim agent file)");
    if (agents.is_relative()) agents = origin.parent_path() / agents;
    if (auto problem = input_file_problem(agents, "HuNavSim agent", kMaxAgentFileBytes))
      fail(file, n, "people_file", fmt::format("'{}' {}", agents.string(), *problem));
    files_read.push_back(agents.string());
    crowd.people = load_hunav_agents(agents);
  }
  if (top.has("people")) {
    const YAML::Node list = checked_list(file, top.get("people"), "people");
    for (std::size_t i = 0; i < list.size(); ++i)
      crowd.people.push_back(read_person(file, list[i], fmt::format("people[{}]", i), i));
  }
  if (top.has("forklifts")) {
    const YAML::Node list = checked_list(file, top.get("forklifts"), "forklifts");
    for (std::size_t i = 0; i < list.size(); ++i)
      crowd.forklifts.push_back(read_forklift(file, list[i], fmt::format("forklifts[{}]", i), i));
  }
  if (crowd.people.size() > kMaxMovers)
    fail(file, top.node(), "people", fmt::format("at most {} people", kMaxMovers));
}

std::optional<RandomPeopleSpec> read_random_people(const std::string& file, MapReader& top) {
  if (!top.has("random_people")) return std::nullopt;
  MapReader r = top.sub("random_people");
  RandomPeopleSpec spec;
  const YAML::Node density = r.require("density", "people per m² of free floor, in (0, 2]");
  spec.density = read_double(file, density, r.path_of("density"));
  if (!(spec.density > 0.0 && spec.density <= 2.0))
    fail(file, density, r.path_of("density"),
         fmt::format("must be in (0, 2] people per m², got {}", spec.density));
  if (r.has("region")) {
    const YAML::Node n = r.get("region");
    const auto b = read_numbers(file, n, r.path_of("region"), 4);
    if (!(b[0] < b[2] && b[1] < b[3]))
      fail(file, n, r.path_of("region"), "expected [xmin, ymin, xmax, ymax] with min < max");
    spec.region = Box2{Vec2(b[0], b[1]), Vec2(b[2], b[3])};
  }
  if (r.has("speed")) {
    const YAML::Node n = r.get("speed");
    const auto v = read_numbers(file, n, r.path_of("speed"), 2);
    if (!(v[0] > 0.0 && v[0] <= v[1] && v[1] <= 10.0))
      fail(file, n, r.path_of("speed"),
           fmt::format("expected [min, max] m/s with 0 < min <= max <= 10, got [{}, {}]", v[0],
                       v[1]));
    spec.min_speed = v[0];
    spec.max_speed = v[1];
  }
  if (r.has("radius")) {
    const YAML::Node n = r.get("radius");
    spec.radius = read_double(file, n, r.path_of("radius"));
    if (!(spec.radius > 0.0 && spec.radius <= 5.0))
      fail(file, n, r.path_of("radius"), fmt::format("must be in (0, 5] m, got {}", spec.radius));
  }
  if (r.has("waypoints")) {
    const YAML::Node n = r.get("waypoints");
    const std::int64_t k = read_int(file, n, r.path_of("waypoints"));
    if (k < 1 || k > static_cast<std::int64_t>(kMaxRoutePoints))
      fail(file, n, r.path_of("waypoints"),
           fmt::format("must be a whole number in [1, {}], got {}", kMaxRoutePoints, k));
    spec.waypoints = static_cast<int>(k);
  }
  r.finish();
  return spec;
}

void add_random_people(const std::string& file, const YAML::Node& root,
                       const RandomPeopleSpec& spec, Scenario& s) {
  const YAML::Node density = root["random_people"]["density"];
  const Box2 region = random_people_region(*s.world, spec);
  if (spec.region &&
      !(s.world->extent().contains(region.min) && s.world->extent().contains(region.max)))
    fail(file, root["random_people"]["region"], "random_people.region",
         "reaches outside the world");
  RandomPeople placed =
      place_random_people(*s.world, spec, s.robots, s.crowd.people, s.crowd.forklifts, s.sim.seed);
  if (placed.asked == 0)
    fail(file, density, "random_people.density",
         fmt::format("{} people per m² of {:.3g} m² of free floor is no one: raise the density "
                     "or widen random_people.region",
                     spec.density, placed.free_area));
  if (placed.people.size() < placed.asked)
    fail(file, density, "random_people.density",
         fmt::format("the floor holds only {} of the {} people asked for ({} per m² of {:.3g} m² "
                     "of free floor, each {} m in radius, 0.1 m apart and outside the robots' "
                     "personal space): lower the density",
                     placed.people.size(), placed.asked, spec.density, placed.free_area,
                     spec.radius));
  if (s.crowd.people.size() + placed.people.size() > kMaxMovers)
    fail(file, density, "random_people.density",
         fmt::format("at most {} people in all, got {}", kMaxMovers,
                     s.crowd.people.size() + placed.people.size()));
  for (PersonSpec& p : placed.people) s.crowd.people.push_back(std::move(p));
}

}  // namespace floornav::io_detail
