#include "floornav/nav/supervisor_guards.hpp"

namespace floornav {

namespace guards {

bool at_goal(const NavigationInput& in, const NavigationParams& p) {
  return in.goal_distance < p.epsilon;
}

bool too_close(const NavigationInput& in, const NavigationParams& p) {
  return in.clearance < p.d_unsafe;
}

bool safe_again(const NavigationInput& in, const NavigationParams& p) {
  return in.clearance >= p.d_unsafe + p.hysteresis;
}

bool clear_shot(const NavigationInput& in, const NavigationParams& p) {
  return p.clear_shot_corridor > 0.0 ? !in.corridor_blocked : in.u_ao.dot(in.u_gtg) > 0.0;
}

bool obstacle_ahead(const NavigationInput& in, const NavigationParams& p, Turn turn) {
  return in.clearance < p.d_o && !clear_shot(in, p) && choose_turn(in.u_gtg, in.u_ao) == turn;
}

bool progress_and_clear_shot(const NavigationInput& in, const NavigationMemory& m,
                             const NavigationParams& p) {
  return in.goal_distance < m.d_tau - p.progress_margin && clear_shot(in, p);
}

bool boundary_lost(const NavigationInput& in) {
  return !in.obstacle_sensed;
}

bool resumes_following(const NavigationInput& in, const NavigationMemory& m,
                       const NavigationParams& p, Turn turn) {
  if (!safe_again(in, p)) return false;
  if (m.following) return m.turn == turn;
  return !clear_shot(in, p) && choose_turn(in.u_gtg, in.u_ao) == turn;
}

bool within_d_o(const NavigationInput& in, const NavigationParams& p) {
  return in.clearance < p.d_o;
}

bool beyond_d_o(const NavigationInput& in, const NavigationParams& p) {
  return in.clearance >= p.d_o;
}

}  // namespace guards

namespace resets {

void start_following(const NavigationInput& in, NavigationMemory& m, Turn turn) {
  m.d_tau = in.goal_distance;
  m.turn = turn;
  m.following = true;
}

void resume_following(const NavigationInput& in, NavigationMemory& m, Turn turn) {
  if (!m.following) m.d_tau = in.goal_distance;
  m.turn = turn;
  m.following = true;
}

void stop_following(NavigationMemory& m) {
  m.following = false;
}

}  // namespace resets

}  // namespace floornav
