// Mapless safety (controller.safety.map: sensed): the layer knows only the robot's returns, and
// those near it that it remembers (sensing/near_point_memory.hpp). The Jackal's 270 degree lidar
// is blind behind: what it saw before turning away must still stop it backing into it.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <utility>

#include "floornav/geometry/angle.hpp"
#include "floornav/scenario/presets.hpp"
#include "floornav/scenario/simulate.hpp"

using namespace floornav;

namespace {

// The Jackal at the origin facing a cylinder (r = 0.2 m, centre 1 m away): it turns on the spot
// until the cylinder lies behind it, stands still until t = `wait_until`, then backs up at
// 0.3 m/s for ever.
Scenario turn_wait_and_back_up(double wait_until, bool safety) {
  const RobotPreset p = *find_robot_preset("jackal");
  WorldDesc d;
  d.circles.push_back({Vec2(-1.0, 0.0), 0.2});
  Scenario s;
  s.name = "mapless-safety";
  s.world = std::make_shared<const World>(std::move(d));
  RobotTask& t = s.robots.emplace_back();
  t.robot = p.robot;
  t.controller.params = p.navigation;
  t.controller.safety.enabled = safety;
  t.controller.safety.map = SafetyMap::Sensed;
  t.start = {Vec2(0.0, 0.0), kPi};
  t.goals = {Vec2(5.0, 0.0)};
  s.sim.dt = 0.05;
  s.sim.t_max = wait_until + 10.0;
  s.sim.stuck_window = 1000.0;  // it turns and waits on the spot on purpose
  s.set_controller("turn_wait_back", make_controller([wait_until](const Observation& obs) {
                     if (std::abs(wrap_angle(obs.pose.theta)) > 0.05 && obs.t < wait_until)
                       return Command::unicycle(0.0, 0.5);
                     if (obs.t < wait_until) return Command::unicycle(0.0, 0.0);
                     return Command::unicycle(-0.3, 0.0);
                   }));
  return s;
}

TEST(MaplessSafety, WithoutTheLayerTheJackalBacksIntoTheCylinderItTurnedAwayFrom) {
  const RunResult r = simulate(turn_wait_and_back_up(15.0, false));
  EXPECT_TRUE(r.collided) << "the scene must drive into the cylinder for the test below to mean "
                             "anything";
}

TEST(MaplessSafety, TheLayerRemembersWhatTheLidarNoLongerSeesAndStops) {
  // Backing up at once, and after standing still for 10 s: the memory keeps by distance, not time.
  for (const double wait_until : {8.0, 20.0}) {
    const RunResult r = simulate(turn_wait_and_back_up(wait_until, true));
    EXPECT_FALSE(r.collided) << "wait until " << wait_until;
    EXPECT_GT(r.min_clearance, 0.0);
    EXPECT_GT(r.safety_steps, 0) << "the layer held the robot back";
    ASSERT_FALSE(r.trajectory.empty());
    // It did back up (the turn ended facing +x, the cylinder's near side is at x = -0.8, the
    // Jackal's rear 0.254 m behind its centre), and stopped short of the cylinder.
    EXPECT_LT(r.trajectory.back().x, -0.2) << "wait until " << wait_until;
    EXPECT_GT(r.trajectory.back().x, -0.8 + 0.254) << "wait until " << wait_until;
    EXPECT_NEAR(std::cos(r.trajectory.back().theta), 1.0, 0.01) << "facing away from it";
  }
}

}  // namespace
