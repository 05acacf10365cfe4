#include "floornav/scenario/validate.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/nav/controller_registry.hpp"
#include "floornav/nav/dwa_controller.hpp"
#include "floornav/nav/navigation_params.hpp"
#include "floornav/nav/sampling_planner.hpp"
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
  // Steps are bounded so that no file can make a run that never ends (the recorded trajectory is
  // bounded again, more tightly, by whoever records it).
  if (sim.t_max / sim.dt > kMaxSteps)
    bad("sim.t_max", fmt::format("t_max / dt = {:.6g} steps, more than the {:.0e} a run may take",
                                 sim.t_max / sim.dt, kMaxSteps));
  if (!(sim.stuck_window > 0.0)) bad("sim.stuck_window", "must be positive");
  if (sim.stuck_radius < 0.0) bad("sim.stuck_radius", "must not be negative");
  if (!(sim.deadlock_window > 0.0)) bad("sim.deadlock_window", "must be positive");
  if (!(sim.livelock_window > 0.0)) bad("sim.livelock_window", "must be positive");
  if (sim.record_ranges_every < 0)
    bad("sim.record_ranges_every",
        fmt::format("must not be negative, got {}", sim.record_ranges_every));
}

// controller.planner: lengths and times that are 0 (derived from the robot) or positive.
void validate_planner(const PlannerParams& p, const RobotKeys& k) {
  auto bad = [&](const char* key, const std::string& what) {
    k.fail(k.controller(std::string("planner.") + key), what);
  };
  auto length = [&](const char* key, double v, double max) {
    if (!(v >= 0.0 && v <= max))
      bad(key, fmt::format("must be in [0, {}] (0: derived from the robot), got {}", max, v));
  };
  length("radius", p.radius, 100.0);
  length("inflation", p.inflation, 100.0);
  length("cell_size", p.cell_size, 10.0);
  length("lookahead", p.lookahead, 1000.0);
  length("progress_distance", p.progress_distance, 1000.0);
  length("backup_distance", p.backup_distance, 100.0);
  length("window", p.window, 1000.0);
  length("sense_range", p.sense_range, 1e6);
  length("memory_range", p.memory_range, 100.0);
  if (!(p.replan_period > 0.0)) bad("replan_period", "must be positive");
  if (!(p.progress_window > 0.0)) bad("progress_window", "must be positive");
  if (!(p.recovery_turn >= 0.0 && p.recovery_turn <= 2.0 * kPi))
    bad("recovery_turn", fmt::format("must be in [0, 2 pi] rad, got {}", p.recovery_turn));
  if (p.max_recoveries < 0 || p.max_recoveries > 1000)
    bad("max_recoveries", fmt::format("must be in [0, 1000], got {}", p.max_recoveries));
  if (!(p.decay > 0.0)) bad("decay", "must be positive");
  if (p.kind == PlannerKind::RrtConnect && !rrt_connect_search()) bad("kind", kNoRrtConnect);
  if (p.max_samples < 1 || p.max_samples > kMaxRrtConnectSamples)
    bad("max_samples",
        fmt::format("must be in [1, {}] (a plan's time grows faster than its samples: 10^6 "
                    "take about 40 s), got {}",
                    kMaxRrtConnectSamples, p.max_samples));
  if (!(p.guard_horizon >= 0.0 && p.guard_horizon <= 10.0))
    bad("guard_horizon", fmt::format("must be in [0, 10] s (0: off), got {}", p.guard_horizon));
  if (!(p.guard_margin >= 0.0 && p.guard_margin <= 1.0))
    bad("guard_margin", fmt::format("must be in [0, 1] m, got {}", p.guard_margin));
  if (p.cell_size > 0.0 && p.window > 0.0 && p.window / p.cell_size > 2000.0)
    bad("window",
        fmt::format("{} m of {} m cells is more than 2000 cells across", p.window, p.cell_size));
}

// controller.dwa: a sampled window and a roll-out of at least one step.
void validate_dwa(const DwaParams& p, const RobotKeys& k) {
  auto bad = [&](const char* key, const std::string& what) {
    k.fail(k.controller(std::string("dwa.") + key), what);
  };
  if (!(p.horizon > 0.0 && p.horizon <= 60.0)) bad("horizon", "must be in (0, 60] s");
  if (!(p.sim_step > 0.0 && p.sim_step <= p.horizon))
    bad("sim_step", fmt::format("must be in (0, horizon = {}] s", p.horizon));
  if (p.horizon / p.sim_step > 1000.0) bad("sim_step", "more than 1000 poses per roll-out");
  if (p.v_samples < 2 || p.v_samples > 200) bad("v_samples", "must be in [2, 200]");
  if (p.omega_samples < 2 || p.omega_samples > 200) bad("omega_samples", "must be in [2, 200]");
  if (!(p.heading >= 0.0)) bad("heading", "must not be negative");
  if (!(p.clearance >= 0.0)) bad("clearance", "must not be negative");
  if (!(p.velocity >= 0.0)) bad("velocity", "must not be negative");
  if (!(p.max_clearance > 0.0)) bad("max_clearance", "must be positive");
  if (!(p.margin >= 0.0)) bad("margin", "must not be negative");
  if (!(p.range >= 0.0 && p.range <= 100.0)) bad("range", "must be in [0, 100] m (0: derived)");
}

// controller.safety: a field of a few centimetres to a metre, a speed cap that is a speed.
void validate_safety(const SafetyParams& p, const RobotKeys& k) {
  auto bad = [&](const char* key, const std::string& what) {
    k.fail(k.controller(std::string("safety.") + key), what);
  };
  if (!(p.margin >= 0.0 && p.margin <= 1.0))
    bad("margin", fmt::format("must be in [0, 1] m, got {}", p.margin));
  if (!(p.reaction_time >= 0.0 && p.reaction_time <= 2.0))
    bad("reaction_time", fmt::format("must be in [0, 2] s, got {}", p.reaction_time));
  if (!(p.slowdown_distance >= 0.0 && p.slowdown_distance <= 10.0))
    bad("slowdown_distance",
        fmt::format("must be in [0, 10] m (0: no slow-down field), got {}", p.slowdown_distance));
  if (!(p.slowdown_speed >= 0.0 && p.slowdown_speed <= 100.0))
    bad("slowdown_speed", fmt::format("must be in [0, 100] m/s, got {}", p.slowdown_speed));
  if (!(p.person_margin >= 0.0 && p.person_margin <= 5.0))
    bad("person_margin", fmt::format("must be in [0, 5] m, got {}", p.person_margin));
}

// controller.robot_avoidance and avoidance_*.
void validate_avoidance(const RobotAvoidanceParams& a, const RobotKeys& k) {
  auto bad = [&](const char* key, const std::string& what) { k.fail(k.controller(key), what); };
  if (!(a.range > 0.0) || a.range > 1000.0) bad("avoidance_range", "must be in (0, 1000] m");
  if (!(a.horizon > 0.0)) bad("avoidance_horizon", "must be positive");
  if (!(a.margin >= 0.0)) bad("avoidance_margin", "must not be negative");
  if (a.neighbours < 1 || a.neighbours > 1000)
    bad("avoidance_neighbours", fmt::format("must be in [1, 1000], got {}", a.neighbours));
}

// The chapter's keys: the guards of Fig 5.11 need d_unsafe < d_fb < d_o, ...
void validate_navigation(const NavigationParams& n, const RobotKeys& k) {
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
  if (!(n.heading_pid.kp >= 0.0)) bad("pid.kp", "must not be negative");
  if (!(n.heading_pid.ki >= 0.0)) bad("pid.ki", "must not be negative");
  if (!(n.heading_pid.kd >= 0.0)) bad("pid.kd", "must not be negative");
  if (!(n.heading_pid.integral_limit >= 0.0)) bad("pid.integral_limit", "must not be negative");
  if (!(n.obstacle_range >= 0.0)) bad("obstacle_range", "must not be negative (0: use all)");
}

// The controller section, layer by layer, then what its kind checks (nav/controller_registry.hpp).
void validate_controller(const RobotTask& t, const RobotKeys& k) {
  const ControllerConfig& c = t.controller;
  validate_navigation(c.params, k);
  validate_planner(c.planner, k);
  validate_dwa(c.dwa, k);
  validate_safety(c.safety, k);
  validate_avoidance(c.avoidance, k);
  const BuiltinController* builtin = c.is_builtin() ? find_builtin_controller(c.kind) : nullptr;
  if (builtin && builtin->check)
    if (const auto problem = builtin->check(c, t.robot))
      k.fail(problem->robot_key ? k.robot(problem->key) : k.controller(problem->key),
             problem->what);
}

// m: a robot's protective field (0 with the safety layer off).
double field_of(const RobotTask& t) {
  return t.controller.safety.enabled ? t.controller.safety.margin : 0.0;
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
  if (!(r.max_acceleration > 0.0)) k.fail(k.robot("max_acceleration"), "must be positive");
  if (!(r.max_angular_acceleration > 0.0))
    k.fail(k.robot("max_angular_acceleration"), "must be positive");
  validate_controller(t, k);

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
  const double start_clearance = body_clearance(w, r, t.start);
  if (w.is_inside_obstacle(start) || start_clearance <= 0.0)
    k.fail(k.robot("start"),
           fmt::format("the robot at ({}, {}) overlaps an obstacle or lies outside the world "
                       "(clearance {:.3g} m, body radius {} m)",
                       start.x(), start.y(), w.clearance(start), r.body_radius));
  if (start_clearance < field_of(t))
    k.fail(k.robot("start"),
           fmt::format("the robot at ({}, {}) is {:.3g} m from an obstacle, inside its protective "
                       "field of {} m (controller.safety.margin)",
                       start.x(), start.y(), start_clearance, field_of(t)));
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

// No two robots may start touching, nor inside either one's protective field (found through a
// neighbour grid: O(robots)).
void validate_starts_apart(const std::vector<RobotTask>& robots, const std::string& file) {
  RobotNeighbourGrid grid;
  std::vector<Vec2> starts;
  double max_radius = 0.0, max_field = 0.0;
  Box2 box{robots[0].start.position, robots[0].start.position};
  for (const RobotTask& t : robots) {
    starts.push_back(t.start.position);
    max_radius = std::max(max_radius, t.robot.body_radius);
    max_field = std::max(max_field, field_of(t));
    box.min = box.min.cwiseMin(t.start.position);
    box.max = box.max.cwiseMax(t.start.position);
  }
  const double reach = 2.0 * max_radius + max_field;
  grid.reset(box, reach, starts.size());
  grid.build(starts, std::vector<std::uint8_t>(starts.size(), 1));
  for (std::size_t i = 0; i < starts.size(); ++i)
    grid.for_each_near(starts[i], reach, [&](std::size_t j) {
      if (j <= i) return;
      const double gap = (starts[j] - starts[i]).norm() - robots[i].robot.body_radius -
                         robots[j].robot.body_radius;
      if (gap <= 0.0)
        throw InputError(file, fmt::format("robots[{}].start", j),
                         fmt::format("touches robot {} ('{}') at ({}, {}): the bodies overlap", i,
                                     robots[i].name, starts[i].x(), starts[i].y()));
      const double field = std::max(field_of(robots[i]), field_of(robots[j]));
      if (gap < field)
        throw InputError(
            file, fmt::format("robots[{}].start", j),
            fmt::format("is {:.3g} m from robot {} ('{}'), inside the protective field of {} m "
                        "(controller.safety.margin): start them further apart",
                        gap, i, robots[i].name, field));
    });
}

// No two people may start with their bodies touching (found through a neighbour grid, as the
// robots' starts): overlapping bodies are no crowd a floor can hold, and starting apart bounds how
// many stand within reach of one another (docs/RELIABILITY.md, "Limits").
void validate_people_apart(const std::vector<PersonSpec>& people, const std::string& file) {
  RobotNeighbourGrid grid;
  std::vector<Vec2> starts;
  double max_radius = 0.0;
  Box2 box{people[0].start, people[0].start};
  for (const PersonSpec& p : people) {
    starts.push_back(p.start);
    max_radius = std::max(max_radius, p.radius);
    box.min = box.min.cwiseMin(p.start);
    box.max = box.max.cwiseMax(p.start);
  }
  grid.reset(box, 2.0 * max_radius, starts.size());
  grid.build(starts, std::vector<std::uint8_t>(starts.size(), 1));
  for (std::size_t i = 0; i < starts.size(); ++i)
    grid.for_each_near(starts[i], people[i].radius + max_radius, [&](std::size_t j) {
      if (j <= i) return;
      if ((starts[j] - starts[i]).norm() <= people[i].radius + people[j].radius)
        throw InputError(file, fmt::format("people[{}] ('{}').start", j, people[j].name),
                         fmt::format("touches person {} ('{}') at ({}, {}): the bodies overlap; "
                                     "start them more than their radii apart",
                                     i, people[i].name, starts[i].x(), starts[i].y()));
    });
}

// People and forklifts: where they start and go must be free floor, not on a robot's start.
void validate_crowd(const Scenario& s, const std::string& file) {
  const World& w = *s.world;
  auto free_floor = [&](const Vec2& p, const std::string& key) {
    if (w.is_inside_obstacle(p) || !(w.clearance(p) > 0.0))
      throw InputError(
          file, key,
          fmt::format("({}, {}) is inside an obstacle or outside the world", p.x(), p.y()));
  };
  auto clear_of_robots = [&](auto gap_to, const std::string& key) {
    for (std::size_t i = 0; i < s.robots.size(); ++i) {
      const RobotTask& t = s.robots[i];
      const double gap = gap_to(t.start.position) - t.robot.body_radius;
      if (gap <= 0.0)
        throw InputError(file, key, fmt::format("touches robot {} ('{}') at its start", i, t.name));
      if (gap < field_of(t))
        throw InputError(file, key,
                         fmt::format("is {:.3g} m from robot {} ('{}') at its start, inside the "
                                     "robot's protective field of {} m (controller.safety.margin)",
                                     gap, i, t.name, field_of(t)));
    }
  };
  const SocialForceParams& sf = s.crowd.social;
  if (!(sf.tau > 0.0 && sf.sigma > 0.0 && sf.r_wall > 0.0 && sf.step_time >= 0.0))
    throw InputError(file, "people", "the social force constants must be positive");
  for (std::size_t a = 0; a < s.crowd.people.size(); ++a) {
    const PersonSpec& p = s.crowd.people[a];
    const std::string key = fmt::format("people[{}] ('{}')", a, p.name);
    if (!(p.speed > 0.0 && p.speed <= 10.0))
      throw InputError(file, key + ".speed",
                       fmt::format("must be in (0, 10] m/s, got {}", p.speed));
    if (!(p.radius > 0.0 && p.radius <= 5.0))
      throw InputError(file, key + ".radius", fmt::format("must be in (0, 5] m, got {}", p.radius));
    // A person may step at most half its body per step, as a robot may.
    if (sf.max_speed_factor * p.speed * s.sim.dt > 0.5 * p.radius)
      throw InputError(file, "sim.dt",
                       fmt::format("{} s is too large for {}: at {:.3g} m/s it moves more than "
                                   "half its radius per step",
                                   s.sim.dt, key, sf.max_speed_factor * p.speed));
    free_floor(p.start, key + ".start");
    for (std::size_t k = 0; k < p.waypoints.size(); ++k)
      free_floor(p.waypoints[k], fmt::format("{}.waypoints[{}]", key, k));
    clear_of_robots([&](const Vec2& q) { return (q - p.start).norm() - p.radius; }, key + ".start");
  }
  if (s.crowd.people.size() > 1) validate_people_apart(s.crowd.people, file);
  for (std::size_t k = 0; k < s.crowd.forklifts.size(); ++k) {
    const ForkliftSpec& f = s.crowd.forklifts[k];
    const std::string key = fmt::format("forklifts[{}] ('{}')", k, f.name);
    if (!(f.speed > 0.0 && f.speed <= 20.0))
      throw InputError(file, key + ".speed",
                       fmt::format("must be in (0, 20] m/s, got {}", f.speed));
    if (f.speed * s.sim.dt > 0.25 * std::min(f.size.x(), f.size.y()))
      throw InputError(file, "sim.dt",
                       fmt::format("{} s is too large for {}: it moves more than a quarter of its "
                                   "width per step",
                                   s.sim.dt, key));
    if (f.size.x() > 100.0 || f.size.y() > 100.0)
      throw InputError(file, key + ".size", "at most 100 m a side");
    for (std::size_t j = 0; j < f.route.size(); ++j)
      free_floor(f.route[j], fmt::format("{}.route[{}]", key, j));
    const Vec2 dir = (f.route[1] - f.route[0]).normalized();
    const OrientedBox start{f.route[0], 0.5 * f.size, dir};
    clear_of_robots([&](const Vec2& q) { return signed_distance(start, q); }, key + ".route[0]");
  }
}

}  // namespace

void validate_scenario(const Scenario& s, const std::string& file) {
  if (!s.world) throw InputError(file, "world", "the scenario has no world");
  if (s.robots.empty()) throw InputError(file, "robots", "the scenario has no robot");
  validate_sim(s.sim, file);
  for (std::size_t i = 0; i < s.robots.size(); ++i)
    validate_robot(s.robots[i], *s.world, s.sim, RobotKeys{file, s.robots_listed, i});
  if (s.robots.size() > 1) validate_starts_apart(s.robots, file);
  if (!s.crowd.empty()) validate_crowd(s, file);
}

}  // namespace floornav
