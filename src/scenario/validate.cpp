#include "floornav/scenario/validate.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cstdint>
#include <vector>

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/nav/navigation_params.hpp"
#include "floornav/robot/body_clearance.hpp"
#include "floornav/sim/robot_neighbour_grid.hpp"
#include "floornav/world/occupancy_grid.hpp"

namespace floornav {

namespace {

/// How the file names a robot's keys: `robot.start` and `goal` for a lone robot, `robots[2].start`
/// and `robots[2].goal` in a list; the controller section is shared, so its keys get the robot
/// as a suffix in a list.
struct RobotKeys {
  std::string file;
  bool listed{false};
  std::size_t index{0};

  std::string robot(const std::string& key) const {
    return listed ? fmt::format("robots[{}].{}", index, key) : "robot." + key;
  }
  std::string goal(std::size_t i, std::size_t count) const {
    const std::string g = count == 1 ? "goal" : fmt::format("goals[{}]", i);
    return listed ? fmt::format("robots[{}].{}", index, g) : g;
  }
  std::string controller(const std::string& key) const {
    return listed ? fmt::format("controller.{} (robots[{}])", key, index) : "controller." + key;
  }
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(file, where, what);
  }
};

void validate_sim(const SimConfig& sim, const std::string& file) {
  auto bad = [&](const std::string& key, const std::string& what) {
    throw InputError(file, key, what);
  };
  if (!(sim.dt > 0.0)) bad("sim.dt", fmt::format("must be positive, got {}", sim.dt));
  if (!(sim.t_max > 0.0) || sim.t_max > 1e6)
    bad("sim.t_max", fmt::format("must be in (0, 1e6] s, got {}", sim.t_max));
  if (sim.t_max / sim.dt > 1e9) bad("sim.t_max", "more than 1e9 steps");
  if (!(sim.stuck_window > 0.0)) bad("sim.stuck_window", "must be positive");
  if (sim.stuck_radius < 0.0) bad("sim.stuck_radius", "must not be negative");
  if (sim.record_ranges_every < 0)
    bad("sim.record_ranges_every",
        fmt::format("must not be negative, got {}", sim.record_ranges_every));
}

// The controller section: the guards of Fig 5.11 need d_unsafe < d_fb < d_o, ...
void validate_controller(const NavigationParams& n, const RobotKeys& k) {
  auto bad = [&](const char* key, const std::string& what) { k.fail(k.controller(key), what); };
  if (!(n.v0 > 0.0)) bad("v0", "must be positive");
  if (!(n.gtg_a > 0.0)) bad("gtg_a", "must be positive");
  if (!(n.epsilon > 0.0)) bad("epsilon", "must be positive");
  if (!(n.d_unsafe >= 0.0)) bad("d_unsafe", "must not be negative");
  if (!(n.d_fb > n.d_unsafe))
    bad("d_fb", fmt::format("must be larger than d_unsafe ({})", n.d_unsafe));
  if (!(n.d_o > n.d_fb)) bad("d_o", fmt::format("must be larger than d_fb ({})", n.d_fb));
  if (!(n.hysteresis >= 0.0)) bad("hysteresis", "must not be negative");
  if (!(n.d_unsafe + n.hysteresis < n.d_o))
    bad("hysteresis", "d_unsafe + hysteresis must stay below d_o");
  if (!(n.progress_margin >= 0.0)) bad("progress_margin", "must not be negative");
  if (!(n.k_fb >= 0.0)) bad("k_fb", "must not be negative");
  if (!(n.blend_far > n.blend_near && n.blend_near >= 0.0))
    bad("blend_far", "need 0 <= blend_near < blend_far");
  if (!(n.obstacle_memory >= 0.0)) bad("obstacle_memory", "must not be negative");
  if (!(n.clear_shot_corridor >= 0.0))
    bad("clear_shot_corridor", "must not be negative (0 turns it off)");
  if (n.chatter_switches < 2 || n.chatter_switches > ChatterMonitor::kCapacity)
    bad("chatter_switches", fmt::format("must be between 2 and {}", ChatterMonitor::kCapacity));
  if (!(n.chatter_window > 0.0)) bad("chatter_window", "must be positive");
  if (n.heading_pid.integral_limit < 0.0) bad("pid.integral_limit", "must not be negative");
}

void validate_robot(const RobotTask& t, const World& w, const SimConfig& sim, const RobotKeys& k) {
  const RobotSpec& r = t.robot;
  const double v_max = max_forward_speed(r.drive);
  // A step must not carry the robot through half its own body: collisions would be missed.
  if (v_max * sim.dt > 0.5 * r.body_radius)
    k.fail("sim.dt" + (k.listed ? fmt::format(" (robots[{}])", k.index) : std::string()),
           fmt::format("{} s is too large: at {:.3g} m/s the robot moves {:.3g} m per step, "
                       "more than half its radius {:.3g} m",
                       sim.dt, v_max, v_max * sim.dt, r.body_radius));
  for (std::size_t i = 0; i < r.sensors.size(); ++i) {
    const RangeSensorSpec& sp = r.sensors[i];
    if (!(sp.min_range >= 0.0 && sp.max_range > sp.min_range))
      k.fail(k.robot("sensors"),
             fmt::format("sensor {}: need 0 <= min_range < max_range, got {} and {}", i,
                         sp.min_range, sp.max_range));
  }
  validate_controller(t.controller.params, k);

  // Without bounds a map is the whole world: off the map is unknown space, not free floor.
  Vec2 map_lo, map_hi;
  const bool map_only = w.grid() != nullptr && !w.bounds();
  if (map_only) w.grid()->world_extent(&map_lo, &map_hi);
  auto off_map = [&](const Vec2& p) { return map_only && !Box2{map_lo, map_hi}.contains(p); };
  const Vec2 start = t.start.position;
  if (off_map(start))
    k.fail(k.robot("start"),
           fmt::format("({}, {}) is outside the map, which spans ({}, {}) to ({}, {}) m", start.x(),
                       start.y(), map_lo.x(), map_lo.y(), map_hi.x(), map_hi.y()));
  if (w.is_inside_obstacle(start) || body_clearance(w, r, t.start) <= 0.0)
    k.fail(k.robot("start"),
           fmt::format("the robot at ({}, {}) overlaps an obstacle or lies outside the world "
                       "(clearance {:.3g} m, body radius {} m)",
                       start.x(), start.y(), w.clearance(start), r.body_radius));
  for (std::size_t i = 0; i < t.goals.size(); ++i) {
    const Vec2 g = t.goals[i];
    const std::string key = k.goal(i, t.goals.size());
    if (off_map(g))
      k.fail(key, fmt::format("({}, {}) is outside the map, which spans ({}, {}) to ({}, {}) m",
                              g.x(), g.y(), map_lo.x(), map_lo.y(), map_hi.x(), map_hi.y()));
    if (w.is_inside_obstacle(g) || w.clearance(g) <= 0.0)
      k.fail(key, fmt::format("({}, {}) is inside an obstacle or outside the world", g.x(), g.y()));
  }
}

// No two robots may start touching (found through a neighbour grid: O(robots)).
void validate_starts_apart(const std::vector<RobotTask>& robots, const std::string& file) {
  RobotNeighbourGrid grid;
  std::vector<Vec2> starts;
  double max_radius = 0.0;
  Box2 box{robots[0].start.position, robots[0].start.position};
  for (const RobotTask& t : robots) {
    starts.push_back(t.start.position);
    max_radius = std::max(max_radius, t.robot.body_radius);
    box.min = box.min.cwiseMin(t.start.position);
    box.max = box.max.cwiseMax(t.start.position);
  }
  grid.reset(box, 2.0 * max_radius, starts.size());
  grid.build(starts, std::vector<std::uint8_t>(starts.size(), 1));
  for (std::size_t i = 0; i < starts.size(); ++i)
    grid.for_each_near(starts[i], 2.0 * max_radius, [&](std::size_t j) {
      const double touch = robots[i].robot.body_radius + robots[j].robot.body_radius;
      if (j > i && (starts[j] - starts[i]).norm() <= touch)
        throw InputError(file, fmt::format("robots[{}].start", j),
                         fmt::format("touches robot {} ('{}') at ({}, {}): the bodies overlap", i,
                                     robots[i].name, starts[i].x(), starts[i].y()));
    });
}

}  // namespace

void validate_scenario(const Scenario& s, const std::string& file) {
  if (!s.world) throw InputError(file, "world", "the scenario has no world");
  if (s.robots.empty()) throw InputError(file, "robots", "the scenario has no robot");
  validate_sim(s.sim, file);
  for (std::size_t i = 0; i < s.robots.size(); ++i)
    validate_robot(s.robots[i], *s.world, s.sim, RobotKeys{file, s.robots_listed, i});
  if (s.robots.size() > 1) validate_starts_apart(s.robots, file);
}

}  // namespace floornav
