#include "floornav/scenario/factory_floor.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/validate.hpp"

namespace floornav {

namespace {

struct Disc {
  Vec2 centre;
  double radius;
};

// A star-shaped polygon about `d.centre`: vertices at evenly spaced angles (jittered by up to a
// third of the spacing) and radii between 0.6 and 1 times `d.radius`. Star-shaped means simple.
std::vector<Vec2> star_polygon(const Disc& d, int vertices, Rng& rng) {
  std::vector<Vec2> poly;
  poly.reserve(static_cast<std::size_t>(vertices));
  const double step = 2.0 * kPi / vertices;
  const double phase = rng.uniform(0.0, step);
  for (int i = 0; i < vertices; ++i) {
    const double a = phase + i * step + rng.uniform(-step / 3.0, step / 3.0);
    const double r = d.radius * rng.uniform(0.6, 1.0);
    poly.emplace_back(d.centre.x() + r * std::cos(a), d.centre.y() + r * std::sin(a));
  }
  return poly;
}

Vec2 pick_free_point(const World& world, Rng& rng, double side, double min_clearance) {
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const Vec2 p(rng.uniform(0.0, side), rng.uniform(0.0, side));
    if (!world.is_inside_obstacle(p) && world.clearance(p) >= min_clearance) return p;
  }
  throw std::runtime_error("factory floor: no free point found");
}

}  // namespace

WorldDesc make_factory_floor(const FactoryFloorParams& p) {
  Rng rng(p.seed);
  WorldDesc desc;
  desc.bounds = Box2{Vec2(0.0, 0.0), Vec2(p.side, p.side)};
  std::vector<Disc> discs;
  const double wall_gap = 0.5 * p.gap;
  for (int attempt = 0; static_cast<int>(discs.size()) < p.polygons; ++attempt) {
    if (attempt > 1000 * (p.polygons + 10))
      throw std::runtime_error("factory floor: " + std::to_string(p.polygons) +
                               " polygons do not fit on a " + std::to_string(p.side) + " m floor");
    const double r = rng.uniform(p.min_radius, p.max_radius);
    const double lo = r + wall_gap, hi = p.side - r - wall_gap;
    if (hi <= lo) continue;
    const Disc d{Vec2(rng.uniform(lo, hi), rng.uniform(lo, hi)), r};
    const bool clear = std::all_of(discs.begin(), discs.end(), [&](const Disc& o) {
      return (o.centre - d.centre).norm() >= o.radius + d.radius + p.gap;
    });
    if (clear) discs.push_back(d);
  }
  const int n = p.polygons;
  for (int i = 0; i < n; ++i) {
    int vertices = 3 + static_cast<int>(rng.uniform() * 6.0);  // 3-8
    if (p.total_edges > 0) {
      // Spread the edges evenly: the first (total % n) polygons take one more.
      vertices = p.total_edges / n + (i < p.total_edges % n ? 1 : 0);
    }
    desc.polygons.push_back(star_polygon(discs[static_cast<std::size_t>(i)], vertices, rng));
  }
  return desc;
}

FactoryFloorParams factory_floor_with_edges(int edges) {
  FactoryFloorParams p;
  p.total_edges = std::max(edges, 3);
  p.polygons = std::max(1, p.total_edges / 8);
  // Same density as the 50-polygon, 20 m floor; never below 4 m so one polygon still fits.
  p.side = std::max(4.0, 20.0 * std::sqrt(p.polygons / 50.0));
  return p;
}

Scenario make_factory_floor_scenario(std::shared_ptr<const World> world, int beams, int index) {
  const bool lidar = beams > 0;
  const RobotPreset preset = *find_robot_preset(lidar ? "turtlebot3_burger" : "quickbot");
  Scenario s;
  s.name = lidar ? "lidar" + std::to_string(beams) + "-floor" : "quickbot-floor";
  s.world = std::move(world);
  RobotTask& t = s.robots.emplace_back();
  t.robot = preset.robot;
  t.controller.params = preset.navigation;
  if (lidar) t.robot.sensors = make_lidar(beams, 2.0 * kPi, 0.12, 3.5, {Vec2(-0.032, 0.0), 0.0});
  s.sim.dt = 0.01;
  s.sim.t_max = 1.0e5;
  s.sim.record_trajectory = false;
  s.sim.seed = 1;

  const double side = s.world->extent().max.x();
  Rng rng(1000 + static_cast<std::uint64_t>(index));
  const double margin = t.robot.body_radius + 0.3;
  const Vec2 start = pick_free_point(*s.world, rng, side, margin);
  t.start = {start, rng.uniform(-kPi, kPi)};
  Vec2 from = start;
  while (t.goals.size() < 4) {
    const Vec2 g = pick_free_point(*s.world, rng, side, margin);
    if ((g - from).norm() < side / 3.0) continue;  // cross the floor, not a step aside
    t.goals.push_back(g);
    from = g;
  }
  validate_scenario(s, s.name);
  return s;
}

Scenario make_generated_floor(const Scenario& base, std::uint64_t seed, const std::string& source) {
  FactoryFloorParams p;
  p.seed = seed;
  auto world = std::make_shared<const World>(make_factory_floor(p));
  // The tour of make_factory_floor_scenario (free start and four goals across the floor) for
  // this seed.
  const Scenario tour = make_factory_floor_scenario(world, 0, static_cast<int>(seed));
  Scenario s = base;
  s.world = world;
  for (RobotTask& t : s.robots) {
    t.start = tour.robot().start;
    t.goals = tour.robot().goals;
  }
  s.name = fmt::format("{}-floor{}", base.name, seed);
  validate_scenario(s, fmt::format("{} (floor {})", source, seed));
  return s;
}

WorldDesc make_fleet_warehouse(int robots) {
  const double side = std::max(20.0, std::sqrt(4.0 * std::max(robots, 1)));
  WorldDesc desc;
  desc.bounds = Box2{Vec2(0.0, 0.0), Vec2(side, side)};
  // Racks 8 m long every 10 m (2 m cross-aisles), rows every 3 m (1 m rack, 2 m aisle).
  for (double y = 2.0; y + 1.0 <= side - 2.0; y += 3.0)
    for (double x = 2.0; x + 8.0 <= side - 2.0; x += 10.0)
      desc.polygons.push_back(
          {Vec2(x, y), Vec2(x + 8.0, y), Vec2(x + 8.0, y + 1.0), Vec2(x, y + 1.0)});
  return desc;
}

Scenario make_fleet_scenario(std::shared_ptr<const World> world, int robots, int beams) {
  Scenario s;
  s.world = world;
  s.name = fmt::format("fleet-{}x-{}", robots, beams > 0 ? fmt::format("lidar{}", beams) : "ir");
  s.sim.dt = 0.01;
  s.sim.t_max = 1.0e5;
  s.sim.record_trajectory = false;
  const double side = world->extent().max.x();
  // Free lattice points, shuffled with a fixed seed: distinct points 0.6 m apart never touch.
  const Scenario model = make_factory_floor_scenario(world, beams, 0);
  const double margin = model.robot().robot.body_radius + 0.1;
  std::vector<Vec2> lattice;
  for (double y = 0.3; y < side; y += 0.6)
    for (double x = 0.3; x < side; x += 0.6)
      if (world->clearance(Vec2(x, y)) >= margin) lattice.emplace_back(x, y);
  if (lattice.size() < static_cast<std::size_t>(robots))
    throw std::runtime_error("fleet bench: the hall is too small for the fleet");
  Rng rng(4242);
  for (std::size_t i = lattice.size() - 1; i > 0; --i)
    std::swap(lattice[i], lattice[static_cast<std::size_t>(rng.uniform() * (i + 1)) % (i + 1)]);
  s.robots.reserve(static_cast<std::size_t>(robots));
  for (int i = 0; i < robots; ++i) {
    RobotTask t = model.robot();
    t.name = fmt::format("r{}", i);
    t.goals.clear();
    t.start = {lattice[static_cast<std::size_t>(i)], rng.uniform(-kPi, kPi)};
    Vec2 from = t.start.position;
    while (t.goals.size() < 4) {
      const Vec2 g = pick_free_point(*world, rng, side, margin);
      if ((g - from).norm() < std::min(side / 3.0, 20.0)) continue;  // cross the hall
      t.goals.push_back(g);
      from = g;
    }
    s.robots.push_back(std::move(t));
  }
  s.robots_listed = true;
  return s;
}

}  // namespace floornav
