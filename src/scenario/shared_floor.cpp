#include "floornav/scenario/shared_floor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/robot/body_clearance.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/validate.hpp"

namespace floornav {

namespace {

// Draws a position until one passes `free` (at most this many tries before the floor gives up a
// robot, person or goal it cannot place).
constexpr int kTries = 400;
// m kept between any two starts or goals beyond the two bodies.
constexpr double kApart = 0.3;
// m: free floor round each start and goal beyond the body.
constexpr double kRoom = 0.15;

int uniform_int(Rng& rng, int lo, int hi) {  // in [lo, hi]
  return lo + static_cast<int>(rng.uniform() * (hi - lo + 1));
}

// A hall of w x h metres with a few pillars and boxes, none on the lane y = lane (if given).
WorldDesc draw_hall(Rng& rng, double w, double h, std::optional<double> lane, double lane_half) {
  WorldDesc d;
  d.bounds = Box2{Vec2(0.0, 0.0), Vec2(w, h)};
  const int pillars = uniform_int(rng, 1, 5), boxes = uniform_int(rng, 1, 5);
  auto off_lane = [&](const Vec2& c, double reach) {
    return !lane || std::abs(c.y() - *lane) > lane_half + reach + 0.1;
  };
  for (int k = 0; k < pillars; ++k) {
    const double r = rng.uniform(0.1, 0.35);
    const Vec2 c(rng.uniform(0.8, w - 0.8), rng.uniform(0.8, h - 0.8));
    if (off_lane(c, r)) d.circles.push_back({c, r});
  }
  for (int k = 0; k < boxes; ++k) {
    const Vec2 half(rng.uniform(0.15, 0.75), rng.uniform(0.15, 0.5));
    const Vec2 c(rng.uniform(1.0, w - 1.0), rng.uniform(1.0, h - 1.0));
    if (!off_lane(c, half.norm())) continue;
    const double a = rng.uniform(0.0, kPi);
    std::vector<Vec2> poly;
    for (const Vec2& corner : {Vec2(-half.x(), -half.y()), Vec2(half.x(), -half.y()),
                               Vec2(half.x(), half.y()), Vec2(-half.x(), half.y())})
      poly.push_back(c + rotate(corner, a));
    d.polygons.push_back(std::move(poly));
  }
  return d;
}

// A robot of the floor: its preset, controller kind and speed.
RobotTask draw_robot(Rng& rng, bool mixed, int index, const RobotTask* given) {
  static constexpr std::array<std::string_view, 5> kPresets{
      "quickbot", "khepera3", "turtlebot3_burger", "pioneer_p3dx", "jackal"};
  static constexpr std::array<std::string_view, 6> kKinds{"hybrid",     "blended", "hard_switch",
                                                          "go_to_goal", "dwa",     "astar"};
  RobotTask t;
  t.name = std::string("r").append(std::to_string(index));
  if (given) {
    t.robot = given->robot;
    t.controller = given->controller;
    return t;
  }
  const std::string_view preset =
      mixed ? kPresets[static_cast<std::size_t>(uniform_int(rng, 0, kPresets.size() - 1))]
            : "quickbot";
  const RobotPreset p = *find_robot_preset(preset);
  t.robot = p.robot;
  t.controller.params = p.navigation;
  if (mixed) {
    const std::string_view kind =
        kKinds[static_cast<std::size_t>(uniform_int(rng, 0, kKinds.size() - 1))];
    if (kind == "astar") {
      t.controller.kind = "hybrid";
      t.controller.planner.kind = PlannerKind::AStar;
    } else {
      t.controller.kind = std::string(kind);
    }
    t.controller.params.v0 =
        std::min(p.navigation.v0 * rng.uniform(0.5, 1.5), max_forward_speed(p.robot.drive));
  }
  return t;
}

}  // namespace

Scenario make_shared_floor(std::uint64_t seed, const SharedFloorOptions& o) {
  Rng rng(seed);
  Scenario s;
  s.name = std::string("shared-floor-").append(std::to_string(seed));
  s.robots_listed = true;
  s.sim.t_max = o.t_max;
  s.sim.seed = seed;
  s.sim.record_trajectory = false;

  const double w = rng.uniform(6.0, 12.0), h = rng.uniform(5.0, 10.0);
  const bool people = rng.uniform() < o.people_share;
  const bool forklift = rng.uniform() < o.forklift_share;
  const Vec2 fork_size(1.6, 0.8);
  const double lane_half = 0.5 * fork_size.y() + 0.3;
  std::optional<double> lane;
  if (forklift) lane = rng.uniform(0.5 * h - 1.0, 0.5 * h + 1.0);
  const auto world = std::make_shared<const World>(draw_hall(rng, w, h, lane, lane_half));
  s.world = world;

  // Starts, goals and people's places: free floor, apart from each other, off the lane.
  struct Placed {
    Vec2 at;
    double radius;
  };
  std::vector<Placed> placed;
  auto place = [&](double radius) -> std::optional<Vec2> {
    for (int k = 0; k < kTries; ++k) {
      const Vec2 p(rng.uniform(0.0, w), rng.uniform(0.0, h));
      if (world->clearance(p) < radius + kRoom) continue;
      if (lane && std::abs(p.y() - *lane) < lane_half + radius + kRoom) continue;
      if (std::any_of(placed.begin(), placed.end(), [&](const Placed& q) {
            return (q.at - p).norm() < q.radius + radius + kApart;
          }))
        continue;
      placed.push_back({p, radius});
      return p;
    }
    return std::nullopt;
  };

  const int robots = uniform_int(rng, o.min_robots, o.max_robots);
  for (int i = 0; i < robots; ++i) {
    RobotTask t = draw_robot(rng, o.mixed, i, o.robot);
    const double r = std::max(t.robot.body_radius, 0.0);
    double reach = r;
    for (const Vec2& q : t.robot.footprint) reach = std::max(reach, q.norm());
    const auto start = place(reach);
    if (!start) continue;
    t.start = {*start, rng.uniform(-kPi, kPi)};
    if (body_clearance(*world, t.robot, t.start) < 0.05) {
      placed.pop_back();
      continue;
    }
    const int goals = uniform_int(rng, 1, 3);
    for (int g = 0; g < goals; ++g)
      if (const auto goal = place(reach)) t.goals.push_back(*goal);
    if (t.goals.empty()) {
      placed.pop_back();
      continue;
    }
    s.robots.push_back(std::move(t));
  }

  if (people) {
    const int n = uniform_int(rng, 1, 4);
    for (int a = 0; a < n; ++a) {
      PersonSpec person;
      person.name = std::string("p").append(std::to_string(a));
      person.radius = rng.uniform(0.2, 0.25);
      person.speed = rng.uniform(0.8, 1.3);
      const auto start = place(person.radius);
      if (!start) continue;
      person.start = *start;
      for (int k = 0; k < 3; ++k)
        if (const auto wp = place(person.radius)) person.waypoints.push_back(*wp);
      if (!person.waypoints.empty()) s.crowd.people.push_back(std::move(person));
    }
  }
  if (lane) {
    ForkliftSpec f;
    f.name = "fork0";
    f.size = fork_size;
    f.speed = rng.uniform(0.6, 1.2);
    f.route = {Vec2(1.2, *lane), Vec2(w - 1.2, *lane)};
    s.crowd.forklifts.push_back(std::move(f));
  }
  return s;
}

Scenario make_shared_floor_case(const Scenario& base, std::uint64_t seed,
                                const std::string& source) {
  SharedFloorOptions o;
  o.robot = &base.robot();
  o.t_max = base.sim.t_max;
  Scenario s = make_shared_floor(seed, o);
  s.sim = base.sim;
  s.sim.seed = seed;
  s.name = fmt::format("{}-shared{}", base.name, seed);
  validate_scenario(s, fmt::format("{} (shared floor {})", source, seed));
  return s;
}

}  // namespace floornav
