#include "floornav/nav/navigation_automaton.hpp"

#include <cmath>

namespace floornav {

NavigationAutomaton make_navigation_automaton(ControllerKind kind, const NavigationParams& p) {
  using In = NavigationInput;
  using Mem = NavigationMemory;
  NavigationAutomaton::Builder b;
  b.set_chatter_rule(p.chatter_switches, p.chatter_window);

  const auto gtg_flow = [](const In& in, const Mem&) { return in.u_gtg; };  // eq. 5.18
  const auto ao_flow = [](const In& in, const Mem&) { return in.u_ao; };    // eq. 5.20
  const auto stop_flow = [](const In&, const Mem&) { return Vec2(Vec2::Zero()); };
  const auto at_goal = [p](const In& in, const Mem&) { return guards::at_goal(in, p); };

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
                 [p](const In& in, const Mem&) { return guards::within_d_o(in, p); });
      b.add_edge(ao, gtg, "obstacle_beyond_d_o",
                 [p](const In& in, const Mem&) { return guards::beyond_d_o(in, p); });
      b.set_initial(gtg);
      break;
    }
    case ControllerKind::Hybrid: {           // Fig 5.11
      const auto fb_flow = [p](Turn turn) {  // eqs. 5.22-5.24
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

      const auto too_close = [p](const In& in, const Mem&) { return guards::too_close(in, p); };
      const auto obstacle_ahead = [p](Turn turn) {
        return [p, turn](const In& in, const Mem&) { return guards::obstacle_ahead(in, p, turn); };
      };
      const auto start_following = [](Turn turn) {
        return [turn](const In& in, Mem& m) { resets::start_following(in, m, turn); };
      };
      const auto stop_following = [](const In&, Mem& m) { resets::stop_following(m); };
      const auto resumes = [p](Turn turn) {
        return [p, turn](const In& in, const Mem& m) {
          return guards::resumes_following(in, m, p, turn);
        };
      };
      const auto resume_reset = [](Turn turn) {
        return [turn](const In& in, Mem& m) { resets::resume_following(in, m, turn); };
      };

      b.add_edge_from_every_mode(stop, "at_goal", at_goal);
      b.add_edge(gtg, ao, "too_close", too_close);
      b.add_edge(gtg, fb_cw, "obstacle_ahead_cw", obstacle_ahead(Turn::Clockwise),
                 start_following(Turn::Clockwise));
      b.add_edge(gtg, fb_ccw, "obstacle_ahead_ccw", obstacle_ahead(Turn::CounterClockwise),
                 start_following(Turn::CounterClockwise));
      for (const int fb : {fb_cw, fb_ccw}) {
        b.add_edge(fb, ao, "too_close", too_close);
        b.add_edge(
            fb, gtg, "progress_and_clear_shot",
            [p](const In& in, const Mem& m) { return guards::progress_and_clear_shot(in, m, p); },
            stop_following);
        b.add_edge(
            fb, gtg, "boundary_lost",
            [](const In& in, const Mem&) { return guards::boundary_lost(in); }, stop_following);
      }
      b.add_edge(ao, fb_cw, "safe_again_cw", resumes(Turn::Clockwise),
                 resume_reset(Turn::Clockwise));
      b.add_edge(ao, fb_ccw, "safe_again_ccw", resumes(Turn::CounterClockwise),
                 resume_reset(Turn::CounterClockwise));
      b.add_edge(ao, gtg, "safe_again_clear_shot",
                 [p](const In& in, const Mem&) { return guards::safe_again(in, p); });
      b.set_initial(gtg);
      break;
    }
  }
  return b.build();
}

}  // namespace floornav
