#include "crowd_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace floornav::io_detail {

namespace {

// A scenario names at most this many people and forklifts (each is simulated every step), and a
// person or route at most this many points.
constexpr std::size_t kMaxMovers = 10000;
constexpr std::size_t kMaxRoutePoints = 1000;
constexpr std::size_t kMaxAgentFileBytes = 4u << 20;

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

// A required child of a HuNavSim map.
YAML::Node child(const std::string& file, const YAML::Node& n, const std::string& path,
                 const std::string& key) {
  if (!n.IsMap()) fail(file, n, path, "expected a mapping");
  const YAML::Node c = n[key];
  if (!c) fail(file, n, path.empty() ? key : path + "." + key, "missing");
  return c;
}

}  // namespace

std::vector<PersonSpec> load_hunav_agents(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(file, "",
                     std::filesystem::exists(path, ec) ? "not a regular file" : "no such file");
  if (std::filesystem::file_size(path, ec) > kMaxAgentFileBytes)
    throw InputError(file, "", "too large for an agent file");
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  YAML::Node root;
  try {
    root = YAML::Load(text.str());
  } catch (const YAML::Exception& e) {
    throw InputError(file, fmt::format("line {}", e.mark.line + 1), "not valid YAML: " + e.msg);
  }
  const std::string base = "hunav_loader.ros__parameters";
  const YAML::Node params =
      child(file, child(file, root, "", "hunav_loader"), "hunav_loader", "ros__parameters");
  const YAML::Node names = child(file, params, base, "agents");
  checked_list(file, names, base + ".agents");
  std::vector<PersonSpec> people;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string name = read_string(file, names[i], fmt::format("{}.agents[{}]", base, i));
    const std::string at = base + "." + name;
    const YAML::Node agent = child(file, params, base, name);
    PersonSpec p;
    p.name = name;
    const YAML::Node pose = child(file, agent, at, "init_pose");
    p.start =
        Vec2(read_double(file, child(file, pose, at + ".init_pose", "x"), at + ".init_pose.x"),
             read_double(file, child(file, pose, at + ".init_pose", "y"), at + ".init_pose.y"));
    auto positive = [&](const char* key, double& field) {
      const YAML::Node n = agent[key];
      if (!n) return;
      field = read_double(file, n, at + "." + key);
      if (!(field > 0.0)) fail(file, n, at + "." + key, "must be positive");
    };
    positive("max_vel", p.speed);
    positive("radius", p.radius);
    positive("goal_radius", p.goal_radius);
    if (agent["cyclic_goals"])
      p.cyclic = read_bool(file, agent["cyclic_goals"], at + ".cyclic_goals");
    const YAML::Node goals = child(file, agent, at, "goals");
    checked_list(file, goals, at + ".goals");
    if (goals.size() == 0) fail(file, goals, at + ".goals", "needs at least one goal");
    for (std::size_t k = 0; k < goals.size(); ++k) {
      const std::string g = read_string(file, goals[k], fmt::format("{}.goals[{}]", at, k));
      const YAML::Node goal = agent[g];
      if (!goal)
        fail(file, goals[k], fmt::format("{}.goals[{}]", at, k),
             fmt::format("no goal '{}' in {}", g, name));
      p.waypoints.emplace_back(
          read_double(file, child(file, goal, at + "." + g, "x"), at + "." + g + ".x"),
          read_double(file, child(file, goal, at + "." + g, "y"), at + "." + g + ".y"));
    }
    people.push_back(std::move(p));
  }
  return people;
}

void read_crowd(const std::string& file, MapReader& top, const std::filesystem::path& origin,
                CrowdSpec& crowd) {
  if (top.has("people_file")) {
    const YAML::Node n = top.get("people_file");
    std::filesystem::path agents = read_string(file, n, "people_file");
    if (agents.is_relative()) agents = origin.parent_path() / agents;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(agents, ec))
      fail(file, n, "people_file", fmt::format("no such file: {}", agents.string()));
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
