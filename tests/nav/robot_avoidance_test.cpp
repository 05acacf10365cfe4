// Robot avoidance (nav/robot_avoidance.hpp): ORCA's constraint and linear programs on values
// worked by hand, which sensed points are a robot's, and the layer around a controller.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "floornav/nav/robot_avoidance.hpp"
#include "floornav/scenario/presets.hpp"

using namespace floornav;

namespace {
// Permitted: on the left of the line (or on it).
bool permits(const OrcaLine& l, const Vec2& v) {
  return cross(l.direction, v - l.point) >= -1e-12;
}
}  // namespace

// Head on: A at the origin at (1, 0), B 4 m ahead at (-1, 0), r = 1, tau = 2. The relative
// velocity (2, 0) points at the centre of the cut-off disc (p / tau = (2, 0)), so the nearest
// way out is the leg: the cone's half-angle is asin(1/4), the change u has length
// |v| sin(half-angle) = 0.5, u = (-1/8, -sqrt(15)/8), and A takes half of it: the line runs
// through (1 - 1/16, -sqrt(15)/16) along (-sqrt(15)/4, 1/4). A keeps right (-y): its own velocity
// is forbidden, moving right is permitted.
TEST(Orca, HeadOnLineWorkedByHand) {
  const OrcaLine l = orca_line(Vec2(4, 0), Vec2(1, 0), Vec2(-1, 0), 1.0, 2.0, 0.01, 0.5);
  const double s15 = std::sqrt(15.0);
  EXPECT_NEAR(l.point.x(), 1.0 - 1.0 / 16.0, 1e-12);
  EXPECT_NEAR(l.point.y(), -s15 / 16.0, 1e-12);
  EXPECT_NEAR(l.direction.x(), -s15 / 4.0, 1e-12);
  EXPECT_NEAR(l.direction.y(), 0.25, 1e-12);
  EXPECT_FALSE(permits(l, Vec2(1, 0)));
  EXPECT_TRUE(permits(l, Vec2(1, -0.5)));
  EXPECT_FALSE(permits(l, Vec2(1, 0.5)));  // not to the left
  // B, seeing the mirror image, also keeps to its own right (+y in the world).
  const OrcaLine m = orca_line(Vec2(-4, 0), Vec2(-1, 0), Vec2(1, 0), 1.0, 2.0, 0.01, 0.5);
  EXPECT_TRUE(permits(m, Vec2(-1, 0.5)));
  EXPECT_FALSE(permits(m, Vec2(-1, -0.5)));
}

// Far apart and moving apart, nothing is forbidden that is near the current velocity.
TEST(Orca, RobotsDrivingApartAreNotHeldBack) {
  const OrcaLine l = orca_line(Vec2(3, 0), Vec2(-0.2, 0), Vec2(0.2, 0), 0.2, 2.0, 0.01, 0.5);
  EXPECT_TRUE(permits(l, Vec2(-0.2, 0)));
  EXPECT_TRUE(permits(l, Vec2(0, 0)));
}

// Overlapping bodies: the line asks for separation within one step: the point lies beyond the
// current velocity, away from the other robot.
TEST(Orca, OverlappingBodiesSeparateWithinAStep) {
  const OrcaLine l = orca_line(Vec2(0.1, 0), Vec2(0, 0), Vec2(0, 0), 0.15, 2.0, 0.01, 0.5);
  // u = (r/dt - |w|) unit_w with w = -p/dt = (-10, 0): u = (15 - 10) (-1, 0); half of it.
  EXPECT_NEAR(l.point.x(), -2.5, 1e-12);
  EXPECT_NEAR(l.point.y(), 0.0, 1e-12);
  EXPECT_FALSE(permits(l, Vec2(0, 0)));
  EXPECT_TRUE(permits(l, Vec2(-2.6, 0)));
}

// A still point 0.5 m ahead, r = 0.1, tau = 0.5: v.x <= (0.5 - 0.1) / 0.5 = 0.8; the origin is
// always permitted, and so is sliding along.
TEST(Orca, StillPointBoundsTheApproachSpeed) {
  const OrcaLine l = still_point_line(Vec2(0.5, 0), 0.1, 0.5);
  EXPECT_TRUE(permits(l, Vec2(0.8, 3.0)));
  EXPECT_FALSE(permits(l, Vec2(0.81, 0)));
  EXPECT_TRUE(permits(l, Vec2::Zero()));
  // Inside the radius: no approach at all, moving away is fine.
  const OrcaLine in = still_point_line(Vec2(0.05, 0), 0.1, 0.5);
  EXPECT_TRUE(permits(in, Vec2::Zero()));
  EXPECT_FALSE(permits(in, Vec2(0.01, 0)));
  EXPECT_TRUE(permits(in, Vec2(-0.3, 0.2)));
}

// The 2D program: the velocity nearest the preferred one on the permitted side, within the
// speed disc.
TEST(Orca, ProgramFindsTheNearestPermittedVelocity) {
  std::vector<OrcaLine> projected;
  const std::vector<OrcaLine> bound{still_point_line(Vec2(0.5, 0), 0.1, 0.5)};  // v.x <= 0.8
  Vec2 v = solve_orca(bound, 1, Vec2(1.0, 0.3), 2.0, projected);
  EXPECT_NEAR(v.x(), 0.8, 1e-12);
  EXPECT_NEAR(v.y(), 0.3, 1e-12);
  // The speed disc: the preferred velocity is shortened to it.
  v = solve_orca({}, 0, Vec2(3.0, 4.0), 1.0, projected);
  EXPECT_NEAR(v.x(), 0.6, 1e-12);
  EXPECT_NEAR(v.y(), 0.8, 1e-12);
}

// Two soft lines that contradict (v.x <= 0.3 and v.x >= 0.5): the 3D program splits the
// violation, v.x = 0.4. With the first made hard (v.x <= 0.2), it is kept: v.x = 0.2.
TEST(Orca, WithNoRoomTheWorstViolationIsSmallestAndHardLinesHold) {
  const OrcaLine at_most{Vec2(0.3, 0), Vec2(0, 1)};    // permitted: x <= 0.3
  const OrcaLine at_least{Vec2(0.5, 0), Vec2(0, -1)};  // permitted: x >= 0.5
  std::vector<OrcaLine> projected;
  const std::vector<OrcaLine> soft{at_most, at_least};
  EXPECT_NEAR(solve_orca(soft, 0, Vec2::Zero(), 1.0, projected).x(), 0.4, 1e-12);
  const std::vector<OrcaLine> hard{OrcaLine{Vec2(0.2, 0), Vec2(0, 1)}, at_least};
  EXPECT_NEAR(solve_orca(hard, 1, Vec2::Zero(), 1.0, projected).x(), 0.2, 1e-12);
}

// Which sensed points are a moving robot's: those on its body (within the tolerance); never
// those of a robot that stands still, nor a wall's.
TEST(Orca, DropsTheReturnsOfMovingRobotsOnly) {
  const std::vector<NearbyRobot> robots{{Vec2(1, 0), Vec2(0.5, 0), 0.1, true}};
  const std::vector<Vec2> points{Vec2(0.9, 0), Vec2(0.5, 0.5), Vec2(1.0, 0.1 + 2e-6)};
  std::vector<Vec2> out(points.size());
  // (1, 0.100002) is 2e-6 beyond the body: farther than the tolerance 1e-6.
  ASSERT_EQ(drop_robot_points(points, robots, 1e-6, out), 2u);
  EXPECT_EQ(out[0], Vec2(0.5, 0.5));
  EXPECT_EQ(out[1], Vec2(1.0, 0.1 + 2e-6));
  EXPECT_EQ(drop_robot_points(points, robots, 3e-6, out), 1u);
  // A robot that stands still is an obstacle like any other.
  const std::vector<NearbyRobot> parked{{Vec2(1, 0), Vec2::Zero(), 0.1, false}};
  EXPECT_EQ(drop_robot_points(points, parked, 1e-6, out), 3u);
}

namespace {
// A controller that drives straight at (1, 0) m/s and remembers what it saw.
class Straight final : public Controller {
 public:
  Decision decide(const Observation& obs) override {
    seen = obs.points.size();
    seen_sensed = obs.sensed.size();
    return Command::velocity(Vec2(0.15, 0.0));
  }
  std::size_t seen{0};
  std::size_t seen_sensed{0};
};

Observation observation(const RobotSpec& robot, const NavigationParams& params,
                        std::span<const Vec2> points, std::span<const NearbyRobot> robots) {
  Observation obs;
  obs.dt = 0.01;
  obs.robot = &robot;
  obs.params = &params;
  obs.points = points;
  obs.sensed = points;
  obs.robots = robots;
  obs.velocity = Vec2(0.15, 0.0);
  return obs;
}
}  // namespace

// With no moving robot near, the layer passes the wrapped controller's command and observation
// unchanged; with one coming head on, the controller no longer sees it and the command keeps to
// the right.
TEST(Orca, TheLayerActsOnlyWhenAMovingRobotIsNear) {
  const RobotSpec robot = find_robot_preset("quickbot")->robot;
  NavigationParams params;
  auto inner = std::make_unique<Straight>();
  Straight* straight = inner.get();
  auto layer = make_orca_layer(std::move(inner), robot, RobotAvoidanceParams{});
  EXPECT_EQ(layer->mode_names(), straight->mode_names());

  const std::vector<Vec2> wall{Vec2(0.0, 0.5)};
  const std::vector<NearbyRobot> parked{{Vec2(0.6, 0), Vec2::Zero(), 0.075, false}};
  std::vector<Vec2> seen{Vec2(0.0, 0.5), Vec2(0.525, 0.0)};
  Decision d = layer->decide(observation(robot, params, seen, parked));
  EXPECT_EQ(d.command.u(), Vec2(0.15, 0.0));
  EXPECT_EQ(straight->seen, 2u);

  const std::vector<NearbyRobot> coming{{Vec2(0.6, 0), Vec2(-0.15, 0), 0.075, true}};
  d = layer->decide(observation(robot, params, seen, coming));
  EXPECT_EQ(straight->seen, 1u);  // the robot's return is gone, the wall's is not
  EXPECT_LT(d.command.u().y(), 0.0);
  EXPECT_LT(d.command.u().x(), 0.15);
}

// ORCA avoids the `neighbours` nearest moving robots: ten robots just behind, driving away, leave
// no room for an eleventh coming head on from farther ahead, which holds the robot back only when
// it is among those avoided.
TEST(Orca, AvoidsTheNearestNeighboursOnly) {
  const RobotSpec robot = find_robot_preset("quickbot")->robot;
  NavigationParams params;
  std::vector<NearbyRobot> robots;
  for (int k = 0; k < 10; ++k)
    robots.push_back({Vec2(-0.3, 0.05 * (k - 4.5)), Vec2(-0.15, 0), 0.075, true});
  robots.push_back({Vec2(0.7, 0), Vec2(-0.15, 0), 0.075, true});
  const std::vector<Vec2> nothing;
  RobotAvoidanceParams ten;
  EXPECT_EQ(ten.neighbours, 10);
  auto layer = make_orca_layer(std::make_unique<Straight>(), robot, ten);
  EXPECT_EQ(layer->decide(observation(robot, params, nothing, robots)).command.u(),
            Vec2(0.15, 0.0));
  RobotAvoidanceParams eleven;
  eleven.neighbours = 11;
  layer = make_orca_layer(std::make_unique<Straight>(), robot, eleven);
  EXPECT_LT(layer->decide(observation(robot, params, nothing, robots)).command.u().x(), 0.15);
}

// A layer looks first where its last k nearest were; when the robots told change more than a step
// allows (one comes from farther to nearest, or all move away at once), it still avoids the k
// nearest: each decision is the one a new layer makes of the same observation.
TEST(Orca, FindsTheNearestAgainWhenTheRobotsToldChange) {
  const RobotSpec robot = find_robot_preset("quickbot")->robot;
  NavigationParams params;
  const std::vector<Vec2> nothing;
  std::vector<NearbyRobot> robots;
  for (int k = 0; k < 10; ++k)
    robots.push_back({Vec2(-0.3, 0.05 * (k - 4.5)), Vec2(-0.15, 0), 0.075, true});
  robots.push_back({Vec2(0.7, 0), Vec2(-0.15, 0), 0.075, true});
  auto layer = make_orca_layer(std::make_unique<Straight>(), robot, RobotAvoidanceParams{});
  const auto decide_as_new = [&] {
    auto fresh = make_orca_layer(std::make_unique<Straight>(), robot, RobotAvoidanceParams{});
    const Vec2 u = layer->decide(observation(robot, params, nothing, robots)).command.u();
    EXPECT_EQ(u, fresh->decide(observation(robot, params, nothing, robots)).command.u());
    return u;
  };
  EXPECT_EQ(decide_as_new(), Vec2(0.15, 0.0));  // the one ahead is not among the ten nearest
  robots.back().position = Vec2(0.25, 0.0);     // now it is, inside the last look
  EXPECT_LT(decide_as_new().x(), 0.15);
  robots.back().position = Vec2(0.7, 0.0);
  EXPECT_EQ(decide_as_new(), Vec2(0.15, 0.0));
  for (int k = 0; k < 10; ++k) robots[k].position.x() = -2.0;  // all beyond the last look
  EXPECT_LT(decide_as_new().x(), 0.15);
}

// A controller that reads the points alone (a built-in kind): the moving robot's return leaves
// its points when they are the returns; with remembered points (kept free of moving robots by the
// memory) the points and the returns pass as they are.
TEST(Orca, AControllerOfPointsAloneKeepsItsReturns) {
  const RobotSpec robot = find_robot_preset("quickbot")->robot;
  NavigationParams params;
  auto inner = std::make_unique<Straight>();
  Straight* straight = inner.get();
  auto layer = make_orca_layer(std::move(inner), robot, RobotAvoidanceParams{}, false);
  const std::vector<NearbyRobot> coming{{Vec2(0.6, 0), Vec2(-0.15, 0), 0.075, true}};
  const std::vector<Vec2> seen{Vec2(0.0, 0.5), Vec2(0.525, 0.0)};
  layer->decide(observation(robot, params, seen, coming));
  EXPECT_EQ(straight->seen, 1u);
  const std::vector<Vec2> remembered{Vec2(0.0, 0.5), Vec2(0.0, -0.5), Vec2(-0.5, 0.0)};
  Observation obs = observation(robot, params, seen, coming);
  obs.points = remembered;
  layer->decide(obs);
  EXPECT_EQ(straight->seen, 3u);
  EXPECT_EQ(straight->seen_sensed, 2u);
}
