// A controller of your own: go to the goal (eqs. 5.16-5.19, written out here) and, near an
// obstacle, go round it with floornav's follow-boundary behaviour (eqs. 5.22-5.24), blended in
// as the obstacle gets closer (eq. 5.21).
// Usage: 01_go_to_goal SCENARIO.yaml   (e.g. scenarios/circle_obstacle.yaml)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>

#include <floornav/floornav.hpp>

class GoToGoal final : public floornav::Controller {
 public:
  GoToGoal() : Controller({"go_to_goal"}) {}

  floornav::Decision decide(const floornav::Observation& obs) override {
    const floornav::NavigationParams& p = *obs.params;  // the scenario's controller section
    if (obs.goal_distance() < p.epsilon) return floornav::Command::goal_reached();

    // Go to goal: u = K e with K = v0 (1 - exp(-a |e|^2)) / |e| (m/s, world frame).
    const floornav::Vec2 x = obs.pose.position;
    const floornav::Vec2 e = obs.goal - x;
    const floornav::Vec2 u_gtg = p.v0 * (1.0 - std::exp(-p.gtg_a * e.squaredNorm())) / e.norm() * e;

    // The nearest sensed point, measured from the body's surface (m).
    double clearance = std::numeric_limits<double>::infinity();
    for (const floornav::Vec2& q : obs.points)
      clearance = std::min(clearance, (q - x).norm() - obs.robot->body_radius);
    // Nothing near, or the goal lies away from what is near (eq. 5.27): straight to the goal.
    const floornav::Vec2 u_ao = floornav::avoid_obstacle_velocity(x, obs.points, p.v0);
    if (clearance > 0.15 || u_ao.dot(u_gtg) > 0.0) {
      turn_.reset();
      return floornav::Command::velocity(u_gtg);
    }
    // An obstacle in the way: go round it, always the same way round (chosen when it was met).
    if (!turn_) turn_ = floornav::choose_turn(u_gtg, u_ao);
    const floornav::Vec2 u_round = floornav::follow_boundary_velocity(
        floornav::normalized_or_zero(u_ao), clearance, *turn_, p.d_fb, p.k_fb, p.v0);
    const double sigma = floornav::blend_weight(clearance, p.d_fb, 0.15);  // 0 far, 1 at d_fb
    // A velocity goes through the chapter's pipeline: heading PID, then wheel saturation.
    return floornav::Command::velocity(floornav::blend_velocities(u_gtg, u_round, sigma));
  }
  void reset() override { turn_.reset(); }  // a run, or the next goal, begins

 private:
  std::optional<floornav::Turn> turn_;
};

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENARIO.yaml\n", argv[0]);
    return 2;
  }
  try {
    floornav::Scenario scenario = floornav::load_scenario_file(argv[1]);
    scenario.set_controller("my_go_to_goal", [](const floornav::ControllerContext&) {
      return std::make_unique<GoToGoal>();
    });
    const floornav::RunResult run = floornav::simulate(scenario);
    std::printf("%s\n", floornav::describe_run(run).c_str());
    return run.reached_goal ? 0 : 1;
  } catch (const floornav::InputError& e) {  // a bad scenario file: file, line and key
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
