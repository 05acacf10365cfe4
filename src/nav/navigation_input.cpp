#include "floornav/nav/navigation_input.hpp"

#include <array>
#include <cmath>

#include "floornav/core/isa_clones.hpp"
#include "floornav/geometry/polygon.hpp"
#include "floornav/nav/behaviours.hpp"

namespace floornav {

namespace {
constexpr std::size_t kMaxNearPoints = 1024;

// u_AO and the clearance from the sensed points to the footprint polygon of `shape`: signed,
// each point in the robot's frame (negative inside).
NavigationInput finish_footprint_input(NavigationInput in, const Vec2& x,
                                       std::span<const Vec2> points, const NavigationParams& p,
                                       const BodyShape& shape) {
  in.u_ao = avoid_obstacle_velocity(x, points, p.v0);
  in.away = normalized_or_zero(in.u_ao);
  const double c = std::cos(shape.heading), s = std::sin(shape.heading);
  for (const Vec2& q : points) {
    const Vec2 d = q - x;
    const Vec2 local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
    const double gap = boundary_distance(shape.footprint, local);
    in.clearance = std::min(in.clearance, contains(shape.footprint, local) ? -gap : gap);
    in.obstacle_sensed = true;
  }
  return in;
}

// With `near_only`, the first kMaxNearPoints of the points within `limit` of x, else all of
// them, against the body disc: make_navigation_input's filter and finish_input's u_AO and
// clearance, bit for bit, in one pass that takes each point's distance once for all three
// (|q - x| and |x - q| are the same bits).
NavigationInput finish_disc_input(NavigationInput in, const Vec2& x, std::span<const Vec2> points,
                                  bool near_only, double limit, double body_radius, double v0) {
  const double limit2 = limit * limit;
  Vec2 sum = Vec2::Zero();
  std::size_t n = 0;
  for (const Vec2& q : points) {
    const Vec2 away = x - q;  // -e, eq. 5.20
    const double d2 = away.squaredNorm();
    if (near_only && !(d2 <= limit2 && n < kMaxNearPoints)) continue;
    ++n;
    const double d = std::sqrt(d2);
    if (!(d2 <= 1e-24)) sum += avoid_obstacle_term(away, d, d2);
    in.clearance = std::min(in.clearance, d - body_radius);
  }
  in.obstacle_sensed = n > 0;
  in.u_ao = v0 * normalized_or_zero(sum);
  in.away = normalized_or_zero(in.u_ao);
  return in;
}
}  // namespace

bool corridor_clear(const Vec2& x, const Vec2& goal, std::span<const Vec2> points, double length,
                    double half_width) {
  const Vec2 d = goal - x;
  const double dist = d.norm();
  if (dist <= 0.0) return true;
  const Vec2 dir = d / dist;
  const double reach = std::min(length, dist);
  for (const Vec2& q : points) {
    const Vec2 r = q - x;
    const double along = r.dot(dir);
    if (along <= 0.0 || along >= reach) continue;
    if (std::abs(r.x() * dir.y() - r.y() * dir.x()) < half_width) return false;
  }
  return true;
}

FLOORNAV_ISA_CLONES
NavigationInput make_navigation_input(const Vec2& x, const Vec2& goal,
                                      std::span<const Vec2> obstacle_points, double body_radius,
                                      const NavigationParams& p, const BodyShape* shape) {
  NavigationInput in;
  in.x = x;
  in.goal = goal;
  in.goal_distance = (goal - x).norm();
  in.u_gtg = go_to_goal_velocity(x, goal, p.v0, p.gtg_a);
  // The corridor looks at every sensed point, however far: it asks about the way ahead.
  if (p.clear_shot_corridor > 0.0)
    in.corridor_blocked =
        !corridor_clear(x, goal, obstacle_points, p.clear_shot_corridor, body_radius + p.d_unsafe);
  if (!(shape && p.footprint_clearance && shape->footprint.size() >= 3))
    return finish_disc_input(in, x, obstacle_points, p.obstacle_range > 0.0,
                             p.obstacle_range + body_radius, body_radius, p.v0);
  if (p.obstacle_range > 0.0) {
    // A long-range lidar sees the whole room; only the obstacles near the robot should push it.
    // The filtered points go to a fixed buffer (no allocation); overflow keeps the first ones.
    std::array<Vec2, kMaxNearPoints> near;
    std::size_t n = 0;
    const double limit = p.obstacle_range + body_radius;
    for (const Vec2& q : obstacle_points)
      if ((q - x).squaredNorm() <= limit * limit && n < near.size()) near[n++] = q;
    return finish_footprint_input(in, x, std::span<const Vec2>(near.data(), n), p, *shape);
  }
  return finish_footprint_input(in, x, obstacle_points, p, *shape);
}

}  // namespace floornav
