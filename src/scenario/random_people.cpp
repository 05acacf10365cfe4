#include "floornav/scenario/random_people.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/oriented_box.hpp"

namespace floornav {

namespace {

// Failed draws in a row after which the floor counts as full.
constexpr int kTries = 2000;
// Draws per waypoint before the walker is drawn again from a new start.
constexpr int kWaypointTries = 200;
// m: the body keeps this much of the world free round a start or waypoint, and this much of
// another person's body.
constexpr double kRoom = 0.1;
// m: what a route's straight legs keep clear of the world beyond the body, sampled this often.
constexpr double kLegRoom = 0.02;
constexpr double kLegStep = 0.02;  // below kLegRoom: the body clears the whole leg
// m: a walker starts at least this far from a forklift's first footprint.
constexpr double kForkliftRoom = 0.3;
// The lattice of free_floor_area: cells of this size, or coarser beyond this many.
constexpr double kAreaCell = 0.05;  // m
constexpr double kMaxAreaCells = 1.0e6;
// Mixed into the scenario's seed: the walkers' draws are their own stream, apart from the
// robots' sensor noise.
constexpr std::uint64_t kStream = 0x70656f706c65ull;  // "people"

bool leg_clear(const World& world, const Vec2& a, const Vec2& b, double radius) {
  const double length = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(length / kLegStep)));
  for (int k = 0; k <= n; ++k) {
    const Vec2 p = a + (b - a) * (static_cast<double>(k) / n);
    if (world.clearance(p) < radius + kLegRoom) return false;
  }
  return true;
}

}  // namespace

Box2 random_people_region(const World& world, const RandomPeopleSpec& spec) {
  if (spec.region) return *spec.region;
  if (world.bounds()) return *world.bounds();
  return world.extent();
}

double free_floor_area(const World& world, const Box2& region) {
  const Vec2 size = region.size();
  if (!(size.x() > 0.0 && size.y() > 0.0)) return 0.0;
  const double cell = std::max(kAreaCell, std::sqrt(size.x() * size.y() / kMaxAreaCells));
  const auto nx = static_cast<long>(std::ceil(size.x() / cell));
  const auto ny = static_cast<long>(std::ceil(size.y() / cell));
  const double wx = size.x() / static_cast<double>(nx), wy = size.y() / static_cast<double>(ny);
  long free = 0;
  for (long j = 0; j < ny; ++j)
    for (long i = 0; i < nx; ++i) {
      const Vec2 p = region.min +
                     Vec2((static_cast<double>(i) + 0.5) * wx, (static_cast<double>(j) + 0.5) * wy);
      if (!world.is_inside_obstacle(p) && world.clearance(p) > 0.0) ++free;
    }
  return static_cast<double>(free) * wx * wy;
}

RandomPeople place_random_people(const World& world, const RandomPeopleSpec& spec,
                                 std::span<const RobotTask> robots,
                                 std::span<const PersonSpec> existing,
                                 std::span<const ForkliftSpec> forklifts, std::uint64_t seed) {
  RandomPeople out;
  const Box2 region = random_people_region(world, spec);
  out.free_area = free_floor_area(world, region);
  out.asked = static_cast<std::size_t>(std::llround(spec.density * out.free_area));
  Rng rng(seed ^ kStream);
  const double r = spec.radius;
  auto draw = [&] {
    return Vec2(rng.uniform(region.min.x(), region.max.x()),
                rng.uniform(region.min.y(), region.max.y()));
  };
  auto fits = [&](const Vec2& p) { return world.clearance(p) >= r + kRoom; };
  auto start_free = [&](const Vec2& p) {
    if (!fits(p)) return false;
    for (const RobotTask& t : robots)
      if ((t.start.position - p).norm() - t.robot.body_radius - r < kPersonalSpace) return false;
    for (const PersonSpec& q : existing)
      if ((q.start - p).norm() < q.radius + r + kRoom) return false;
    for (const PersonSpec& q : out.people)
      if ((q.start - p).norm() < q.radius + r + kRoom) return false;
    for (const ForkliftSpec& f : forklifts) {
      const OrientedBox box{f.route[0], 0.5 * f.size, (f.route[1] - f.route[0]).normalized()};
      if (signed_distance(box, p) < r + kForkliftRoom) return false;
    }
    return true;
  };

  int failed = 0;  // draws in a row that placed no one
  while (out.people.size() < out.asked && failed < kTries) {
    ++failed;
    PersonSpec person;
    person.start = draw();
    if (!start_free(person.start)) continue;
    bool routed = true;
    for (int k = 0; k < spec.waypoints && routed; ++k) {
      const Vec2 from = k == 0 ? person.start : person.waypoints.back();
      routed = false;
      for (int w = 0; w < kWaypointTries; ++w) {
        const Vec2 p = draw();
        if (!fits(p) || !leg_clear(world, from, p, r)) continue;
        // The last waypoint leads back to the first.
        if (k + 1 == spec.waypoints && k > 0 && !leg_clear(world, p, person.waypoints[0], r))
          continue;
        person.waypoints.push_back(p);
        routed = true;
        break;
      }
    }
    if (!routed) continue;
    person.name = "walker" + std::to_string(out.people.size());
    person.speed = rng.uniform(spec.min_speed, spec.max_speed);
    person.radius = r;
    out.people.push_back(std::move(person));
    failed = 0;
  }
  return out;
}

}  // namespace floornav
