// The course's week-7 supervisor (Sim.I.Am / pySimiam, "week 7": go to goal, avoid obstacles,
// follow the wall on the left or the right), written as a student writes it: a supervisor class
// with its own guards (at_goal, unsafe, at_obstacle with the sliding-mode test, progress_made,
// obstacle_cleared) and a switch on the current state, driving floornav's behaviours.
// Usage: 02_week7_supervisor SCENARIO.yaml   (e.g. scenarios/week7_pocket.yaml)
#include <algorithm>
#include <cstdio>
#include <limits>
#include <memory>

#include <floornav/floornav.hpp>

namespace {

using floornav::Command;
using floornav::Turn;
using floornav::Vec2;

class Week7Supervisor final : public floornav::Controller {
 public:
  enum State { kGoToGoal, kAvoidObstacles, kFollowWallLeft, kFollowWallRight };
  enum Event {
    kAtGoal,
    kUnsafe,
    kAtObstacleSlidingLeft,
    kAtObstacleSlidingRight,
    kProgressMade,
    kWallLost,
    kObstacleCleared
  };

  explicit Week7Supervisor(const floornav::NavigationParams& p)
      : Controller({"go_to_goal", "avoid_obstacles", "follow_wall_left", "follow_wall_right"},
                   {"at_goal", "unsafe", "at_obstacle_sliding_left", "at_obstacle_sliding_right",
                    "progress_made", "wall_lost", "obstacle_cleared"}),
        p_(p) {}

  void reset() override {
    state_ = kGoToGoal;
    d_tau_ = kFar;
    came_from_ = kGoToGoal;
  }
  int mode() const override { return state_; }

  floornav::Decision decide(const floornav::Observation& obs) override {
    estimate(obs);
    const int event = execute();
    if (event == kAtGoal) return {Command::goal_reached(), state_, event};
    return {Command::velocity(behaviour()), state_, event};
  }

 private:
  static constexpr double kFar = std::numeric_limits<double>::infinity();

  // What the supervisor knows this step: the behaviours' vectors and the distances.
  void estimate(const floornav::Observation& obs) {
    x_ = obs.pose.position;
    goal_distance_ = obs.goal_distance();
    u_gtg_ = floornav::go_to_goal_velocity(x_, obs.goal, p_.v0, p_.gtg_a);
    u_ao_ = floornav::avoid_obstacle_velocity(x_, obs.points, p_.v0);
    clearance_ = kFar;
    for (const Vec2& q : obs.points)
      clearance_ = std::min(clearance_, (q - x_).norm() - obs.robot->body_radius);
  }

  // The student's guards.
  bool at_goal() const { return goal_distance_ < p_.epsilon; }
  bool unsafe() const { return clearance_ < p_.d_unsafe; }
  bool at_obstacle() const { return clearance_ < p_.d_o; }
  bool obstacle_cleared() const { return clearance_ >= p_.d_unsafe + p_.hysteresis; }
  bool progress_made() const { return goal_distance_ < d_tau_ - p_.progress_margin; }
  // The sliding-mode test: u_fw lies between u_gtg and u_ao, i.e. u_fw = s1 u_gtg + s2 u_ao with
  // s1, s2 > 0 (solve the 2 x 2 system). Then following the wall that way makes progress.
  bool sliding(Turn turn) const {
    const Vec2 u_fw = floornav::follow_boundary_tangent(u_ao_, turn);
    const double det = u_gtg_.x() * u_ao_.y() - u_ao_.x() * u_gtg_.y();
    if (det == 0.0) return false;
    const double s1 = (u_fw.x() * u_ao_.y() - u_ao_.x() * u_fw.y()) / det;
    const double s2 = (u_gtg_.x() * u_fw.y() - u_fw.x() * u_gtg_.y()) / det;
    return s1 > 0.0 && s2 > 0.0;
  }
  static Turn turn_of(State s) {
    return s == kFollowWallLeft ? Turn::CounterClockwise : Turn::Clockwise;  // wall on the left
  }

  // The supervisor's execute(): at most one switch, returning the event that caused it (-1: none).
  int execute() {
    if (at_goal()) return kAtGoal;
    switch (state_) {
      case kGoToGoal:
        if (unsafe()) return to(kAvoidObstacles, kUnsafe);
        if (at_obstacle() && sliding(Turn::CounterClockwise))
          return start_following(kFollowWallLeft, kAtObstacleSlidingLeft);
        if (at_obstacle() && sliding(Turn::Clockwise))
          return start_following(kFollowWallRight, kAtObstacleSlidingRight);
        break;
      case kFollowWallLeft:
      case kFollowWallRight:
        if (unsafe()) return to(kAvoidObstacles, kUnsafe);
        if (progress_made() && !sliding(turn_of(state_))) return to(kGoToGoal, kProgressMade);
        if (clearance_ == kFar) return to(kGoToGoal, kWallLost);
        break;
      case kAvoidObstacles:
        if (obstacle_cleared()) return to(came_from_, kObstacleCleared);
        break;
    }
    return -1;
  }
  int start_following(State s, Event e) {
    d_tau_ = goal_distance_;  // progress is measured from where the wall was met
    return to(s, e);
  }
  int to(State s, Event e) {
    if (s == kAvoidObstacles) came_from_ = state_;
    state_ = s;
    return e;
  }

  Vec2 behaviour() const {
    switch (state_) {
      case kAvoidObstacles:
        return u_ao_;
      case kFollowWallLeft:
      case kFollowWallRight:
        return floornav::follow_boundary_velocity(floornav::normalized_or_zero(u_ao_), clearance_,
                                                  turn_of(state_), p_.d_fb, p_.k_fb, p_.v0);
      case kGoToGoal:
      default:
        return u_gtg_;
    }
  }

  floornav::NavigationParams p_;
  State state_{kGoToGoal};
  State came_from_{kGoToGoal};
  double d_tau_{kFar};
  Vec2 x_{Vec2::Zero()}, u_gtg_{Vec2::Zero()}, u_ao_{Vec2::Zero()};
  double goal_distance_{0.0};
  double clearance_{kFar};
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENARIO.yaml\n", argv[0]);
    return 2;
  }
  try {
    floornav::Scenario scenario = floornav::load_scenario_file(argv[1]);
    // One supervisor per robot, tuned by the robot's controller section (preset defaults + file).
    scenario.set_controller("week7_supervisor", [](const floornav::ControllerContext& c) {
      return std::make_unique<Week7Supervisor>(c.params);
    });
    const floornav::RunResult run = floornav::simulate(scenario);
    std::printf("%s\n", floornav::describe_run(run).c_str());
    for (std::size_t m = 0; m < run.mode_names.size(); ++m)
      std::printf("  %-18s %5.1f s\n", run.mode_names[m].c_str(), run.mode_time[m]);
    return run.reached_goal ? 0 : 1;
  } catch (const floornav::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
