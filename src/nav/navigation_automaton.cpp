#include "floornav/nav/navigation_automaton.hpp"

#include <array>
#include <cmath>

#include "floornav/geometry/polygon.hpp"

namespace floornav {

namespace {
constexpr std::array<std::pair<ControllerKind, std::string_view>, 4> kKindNames{{
    {ControllerKind::GoToGoal, "go_to_goal"},
    {ControllerKind::HardSwitch, "hard_switch"},
    {ControllerKind::Blended, "blended"},
    {ControllerKind::Hybrid, "hybrid"},
}};

// Eq. 5.27, <u_AO, u_GTG> > 0; or, with the corridor extension on, a free corridor.
bool clear_shot(const NavigationInput& in, bool corridor) {
  return corridor ? !in.corridor_blocked : in.u_ao.dot(in.u_gtg) > 0.0;
}

// No sensed point in the rectangle of half-width `half_width` from x towards the goal, `length`
// long: the robot's body could drive straight at the goal that far.
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
}  // namespace

std::optional<ControllerKind> parse_controller_kind(std::string_view name) {
  for (const auto& [kind, text] : kKindNames)
    if (text == name) return kind;
  return std::nullopt;
}

std::string_view to_string(ControllerKind kind) {
  for (const auto& [k, text] : kKindNames)
    if (k == kind) return text;
  return "unknown";
}

namespace {
constexpr std::size_t kMaxNearPoints = 1024;

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

NavigationAutomaton make_navigation_automaton(ControllerKind kind, const NavigationParams& p) {
  using In = NavigationInput;
  using Mem = NavigationMemory;
  NavigationAutomaton::Builder b;
  b.set_chatter_rule(p.chatter_switches, p.chatter_window);

  const auto gtg_flow = [](const In& in, const Mem&) { return in.u_gtg; };
  const auto ao_flow = [](const In& in, const Mem&) { return in.u_ao; };
  const auto stop_flow = [](const In&, const Mem&) { return Vec2(Vec2::Zero()); };
  const auto at_goal = [eps = p.epsilon](const In& in, const Mem&) {
    return in.goal_distance < eps;
  };

  switch (kind) {
    case ControllerKind::GoToGoal: {
      const int gtg = b.add_mode(mode_names::kGoToGoal, gtg_flow);
      const int stop = b.add_mode(mode_names::kStop, stop_flow, true);
      b.add_edge(gtg, stop, "at_goal", at_goal);
      b.set_initial(gtg);
      break;
    }
    case ControllerKind::Blended: {
      const int blend = b.add_mode(mode_names::kBlended, [p](const In& in, const Mem&) {
        const double sigma = blend_weight(in.clearance, p.blend_near, p.blend_far);
        return blend_velocities(in.u_gtg, in.u_ao, sigma);  // eq. 5.21
      });
      const int stop = b.add_mode(mode_names::kStop, stop_flow, true);
      b.add_edge(blend, stop, "at_goal", at_goal);
      b.set_initial(blend);
      break;
    }
    case ControllerKind::HardSwitch: {  // Fig 5.7
      const int gtg = b.add_mode(mode_names::kGoToGoal, gtg_flow);
      const int ao = b.add_mode(mode_names::kAvoidObstacle, ao_flow);
      const int stop = b.add_mode(mode_names::kStop, stop_flow, true);
      b.add_edge_from_every_mode(stop, "at_goal", at_goal);
      b.add_edge(gtg, ao, "obstacle_within_d_o",
                 [d_o = p.d_o](const In& in, const Mem&) { return in.clearance < d_o; });
      b.add_edge(ao, gtg, "obstacle_beyond_d_o",
                 [d_o = p.d_o](const In& in, const Mem&) { return in.clearance >= d_o; });
      b.set_initial(gtg);
      break;
    }
    case ControllerKind::Hybrid: {  // Fig 5.11
      const auto fb_flow = [p](Turn turn) {
        return [p, turn](const In& in, const Mem&) -> Vec2 {
          if (!in.obstacle_sensed) return in.u_gtg;  // nothing to follow: head for the goal
          return follow_boundary_velocity(in.away, in.clearance, turn, p.d_fb, p.k_fb, p.v0);
        };
      };
      const int gtg = b.add_mode(mode_names::kGoToGoal, gtg_flow);
      const int fb_cw = b.add_mode(mode_names::kFollowCw, fb_flow(Turn::Clockwise));
      const int fb_ccw = b.add_mode(mode_names::kFollowCcw, fb_flow(Turn::CounterClockwise));
      const int ao = b.add_mode(mode_names::kAvoidObstacle, ao_flow);
      const int stop = b.add_mode(mode_names::kStop, stop_flow, true);

      const auto too_close = [d = p.d_unsafe](const In& in, const Mem&) {
        return in.clearance < d;
      };
      const auto safe_again = [d = p.d_unsafe + p.hysteresis](const In& in) {
        return in.clearance >= d;
      };
      // GTG -> FB: met an obstacle that is in the way, direction by eqs. 5.23/5.24.
      const bool corridor = p.clear_shot_corridor > 0.0;
      const auto meets = [d_o = p.d_o, corridor](const In& in, Turn turn) {
        return in.clearance < d_o && !clear_shot(in, corridor) &&
               choose_turn(in.u_gtg, in.u_ao) == turn;
      };
      const auto start_following = [](Turn turn) {
        return [turn](const In& in, Mem& m) {
          m.d_tau = in.goal_distance;  // the reset of Fig 5.11
          m.turn = turn;
          m.following = true;
        };
      };
      const auto stop_following = [](const In&, Mem& m) { m.following = false; };

      b.add_edge_from_every_mode(stop, "at_goal", at_goal);
      b.add_edge(gtg, ao, "too_close", too_close);
      b.add_edge(
          gtg, fb_cw, "obstacle_ahead_cw",
          [meets](const In& in, const Mem&) { return meets(in, Turn::Clockwise); },
          start_following(Turn::Clockwise));
      b.add_edge(
          gtg, fb_ccw, "obstacle_ahead_ccw",
          [meets](const In& in, const Mem&) { return meets(in, Turn::CounterClockwise); },
          start_following(Turn::CounterClockwise));
      const auto progress_and_clear_shot = [delta = p.progress_margin, corridor](const In& in,
                                                                                 const Mem& m) {
        return in.goal_distance < m.d_tau - delta && clear_shot(in, corridor);  // 5.26, 5.27
      };
      const auto boundary_lost = [](const In& in, const Mem&) { return !in.obstacle_sensed; };
      for (const int fb : {fb_cw, fb_ccw}) {
        b.add_edge(fb, ao, "too_close", too_close);
        b.add_edge(fb, gtg, "progress_and_clear_shot", progress_and_clear_shot, stop_following);
        b.add_edge(fb, gtg, "boundary_lost", boundary_lost, stop_following);
      }
      // AO -> FB: back in the direction the episode took; a fresh episode picks its direction
      // and stores d_tau like GTG -> FB does.
      const auto resumes = [safe_again, corridor](Turn turn) {
        return [safe_again, turn, corridor](const In& in, const Mem& m) {
          if (!safe_again(in)) return false;
          if (m.following) return m.turn == turn;
          return !clear_shot(in, corridor) && choose_turn(in.u_gtg, in.u_ao) == turn;
        };
      };
      const auto resume_reset = [](Turn turn) {
        return [turn](const In& in, Mem& m) {
          if (!m.following) m.d_tau = in.goal_distance;
          m.turn = turn;
          m.following = true;
        };
      };
      b.add_edge(ao, fb_cw, "safe_again_cw", resumes(Turn::Clockwise),
                 resume_reset(Turn::Clockwise));
      b.add_edge(ao, fb_ccw, "safe_again_ccw", resumes(Turn::CounterClockwise),
                 resume_reset(Turn::CounterClockwise));
      b.add_edge(ao, gtg, "safe_again_clear_shot",
                 [safe_again](const In& in, const Mem&) { return safe_again(in); });
      b.set_initial(gtg);
      break;
    }
  }
  return b.build();
}

}  // namespace floornav
