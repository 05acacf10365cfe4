// A fleet with a controller per robot: every robot of a fleet scenario gets its own instance of a
// user's controller, made by a factory that is told which robot it is for (ControllerContext);
// every other robot keeps the built-in controller of the scenario file. The robots see each
// other with their range sensors, as obstacles.
// Usage: 04_fleet SCENARIO.yaml   (a scenario with a robots: list, e.g.
// scenarios/fleet_crossing.yaml)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include <floornav/floornav.hpp>

namespace {

using floornav::Command;
using floornav::Vec2;

// Go to goal, blending in avoid-obstacle near whatever is sensed (walls or other robots), at a
// cruise speed of the factory's choosing.
class Courteous final : public floornav::Controller {
 public:
  explicit Courteous(double v0) : Controller({"courteous"}), v0_(v0) {}

  floornav::Decision decide(const floornav::Observation& obs) override {
    const floornav::NavigationParams& p = *obs.params;
    if (obs.goal_distance() < p.epsilon) return Command::goal_reached();
    const Vec2 x = obs.pose.position;
    double clearance = std::numeric_limits<double>::infinity();
    for (const Vec2& q : obs.points)
      clearance = std::min(clearance, (q - x).norm() - obs.robot->body_radius);
    const double sigma = floornav::blend_weight(clearance, 0.03, 0.2);
    return Command::velocity(
        floornav::blend_velocities(floornav::go_to_goal_velocity(x, obs.goal, v0_, p.gtg_a),
                                   floornav::avoid_obstacle_velocity(x, obs.points, v0_), sigma));
  }

 private:
  double v0_;  // m/s
};

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENARIO.yaml\n", argv[0]);
    return 2;
  }
  try {
    floornav::Scenario scenario = floornav::load_scenario_file(argv[1]);
    // Every second robot drives with the user's controller: the factory is called once per
    // robot (its own instance, its own state) and may tune it by robot: here the speed.
    const floornav::ControllerFactory courteous = [](const floornav::ControllerContext& c) {
      return std::make_unique<Courteous>(c.robot_index % 4 == 0 ? c.params.v0 : 0.8 * c.params.v0);
    };
    for (std::size_t i = 0; i < scenario.robots.size(); i += 2) {
      scenario.robots[i].controller.kind = "courteous";
      scenario.robots[i].controller.factory = courteous;
    }
    const floornav::FleetResult fleet = floornav::simulate_fleet(scenario, 2);
    for (std::size_t i = 0; i < fleet.robots.size(); ++i) {
      const floornav::RunResult& r = fleet.robots[i];
      std::printf("%-8s %-9s %-10s %5.1f s, path %.2f m\n", r.scenario.c_str(),
                  scenario.robots[i].controller.kind.c_str(),
                  std::string(floornav::to_string(r.status)).c_str(), r.sim_time, r.path_length);
    }
    std::printf("%s\n", floornav::describe_fleet(fleet).c_str());
    return fleet.reached == static_cast<int>(fleet.robots.size()) ? 0 : 1;
  } catch (const floornav::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
