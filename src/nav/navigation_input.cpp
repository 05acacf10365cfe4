#include "floornav/nav/navigation_input.hpp"

#include <array>
#include <cmath>

#include "floornav/geometry/polygon.hpp"
#include "floornav/nav/behaviours.hpp"

namespace floornav {

namespace {
constexpr std::size_t kMaxNearPoints = 1024;

// u_AO and the clearance from the sensed points: to the body disc, or to the footprint polygon.
NavigationInput finish_input(NavigationInput in, const Vec2& x, std::span<const Vec2> points,
                             double body_radius, const NavigationParams& p,
                             const BodyShape* shape) {
  in.u_ao = avoid_obstacle_velocity(x, points, p.v0);
  in.away = normalized_or_zero(in.u_ao);
  if (shape && p.footprint_clearance && shape->footprint.size() >= 3) {
    // Each point in the robot's frame, against the footprint: signed (negative inside).
    const double c = std::cos(shape->heading), s = std::sin(shape->heading);
    for (const Vec2& q : points) {
      const Vec2 d = q - x;
      const Vec2 local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
      const double gap = boundary_distance(shape->footprint, local);
      in.clearance = std::min(in.clearance, contains(shape->footprint, local) ? -gap : gap);
      in.obstacle_sensed = true;
    }
    return in;
  }
  for (const Vec2& q : points) {
    in.clearance = std::min(in.clearance, (q - x).norm() - body_radius);
    in.obstacle_sensed = true;
  }
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
  if (p.obstacle_range > 0.0) {
    // A long-range lidar sees the whole room; only the obstacles near the robot should push it.
    // The filtered points go to a fixed buffer (no allocation); overflow keeps the nearest ones.
    std::array<Vec2, kMaxNearPoints> near;
    std::size_t n = 0;
    const double limit = p.obstacle_range + body_radius;
    for (const Vec2& q : obstacle_points)
      if ((q - x).squaredNorm() <= limit * limit && n < near.size()) near[n++] = q;
    return finish_input(in, x, std::span<const Vec2>(near.data(), n), body_radius, p, shape);
  }
  return finish_input(in, x, obstacle_points, body_radius, p, shape);
}

}  // namespace floornav
