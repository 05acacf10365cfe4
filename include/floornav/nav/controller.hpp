#pragma once
/// @file
/// The controller interface: what a robot's decision-maker sees at each step (an Observation) and
/// what it may ask for (a Command). The four built-in kinds (navigation_controller.hpp) implement
/// it; so can anyone, without touching floornav: derive from Controller, or wrap a callable with
/// `make_controller`, and give the factory to a robot's ControllerConfig.
///
/// Whatever the command, the simulator drives the robot through the same pipeline: a velocity u
/// for the point robot goes through the chapter's differential-drive pipeline (Fig 5.12,
/// eqs. 5.28-5.31: theta_d = atan2(u_2, u_1), the heading PID, V = |u| capped); a unicycle
/// (V, omega) and wheel speeds skip the PID; all three then pass the same wheel mapping and
/// saturation (eqs. 5.10/5.11, "ensure omega").

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "floornav/core/param_fields.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/geometry/vec2.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/nav/dwa_params.hpp"
#include "floornav/nav/navigation_params.hpp"
#include "floornav/nav/planner_params.hpp"
#include "floornav/nav/robot_avoidance_params.hpp"
#include "floornav/nav/safety_params.hpp"
#include "floornav/robot/robot_spec.hpp"
#include "floornav/sensing/range_sensor.hpp"

namespace floornav {

class World;
/// Another robot of the fleet as this robot knows it at the start of a step: not sensed but told,
/// as fleet robots broadcast their pose and velocity (over a fleet server or robot-to-robot
/// radio), one step old. Only robots within `controller.avoidance_range` of this one are told,
/// and only to robots that use robot avoidance (nav/robot_avoidance.hpp).
struct NearbyRobot {
  Vec2 position{Vec2::Zero()};  ///< m, world frame: the body's centre
  Vec2 velocity{Vec2::Zero()};  ///< m/s, world frame: V (cos theta, sin theta) last driven
  double radius{0.0};           ///< m: the body disc
  bool moving{false};           ///< still running (a robot that has finished stands still)
};

/// What a controller sees at one step. The spans point into the simulator's buffers and are
/// valid only during the call.
struct Observation {
  double t{0.0};                      ///< s, time at the start of this step
  double dt{0.0};                     ///< s, the step
  Pose2 pose{};                       ///< x, y (m), theta (rad), world frame
  Vec2 goal{Vec2::Zero()};            ///< m, the current goal
  int goal_index{0};                  ///< which goal of the route (0-based)
  int goal_count{0};                  ///< goals in the route
  std::span<const double> ranges;     ///< m, one per sensor in the robot's order (max: nothing)
  std::span<const SensorBeam> beams;  ///< each sensor's axis in the world frame at this step
  std::span<const Vec2> sensed;       ///< m, world frame: this step's returns, one per hit
  /// m, world frame: the returns plus the remembered ones (controller.obstacle_memory); what the
  /// built-in behaviours use.
  std::span<const Vec2> points;
  /// Other robots near this one, as they broadcast them (NearbyRobot); empty for a lone robot
  /// and for robots that do not use robot avoidance.
  std::span<const NearbyRobot> robots;
  Vec2 velocity{Vec2::Zero()};              ///< m/s, world frame: this robot's last driven V
  const RobotSpec* robot{nullptr};          ///< the robot's base, body and sensors
  const NavigationParams* params{nullptr};  ///< the controller section's chapter keys

  /// |x - x_g|, m.
  double goal_distance() const { return (goal - pose.position).norm(); }
};

/// What a controller asks for at one step.
class Command {
 public:
  enum class Kind {
    Velocity,     ///< u, m/s world frame, for the point robot: through the pipeline of Fig 5.12
    Unicycle,     ///< (V, omega): m/s, rad/s
    Wheels,       ///< (w_left, w_right): rad/s
    GoalReached,  ///< the current goal is reached (STOP): the robot turns to the next one
    Stuck,        ///< the controller gives up (nothing it tried helped): the run ends `stuck`
  };

  static Command velocity(const Vec2& u) { return {Kind::Velocity, u.x(), u.y()}; }
  static Command unicycle(double v, double omega) { return {Kind::Unicycle, v, omega}; }
  static Command wheels(double left, double right) { return {Kind::Wheels, left, right}; }
  static Command goal_reached() { return {Kind::GoalReached, 0.0, 0.0}; }
  static Command stuck() { return {Kind::Stuck, 0.0, 0.0}; }

  Kind kind() const { return kind_; }
  Vec2 u() const { return {a_, b_}; }  ///< Velocity
  UnicycleCommand unicycle_command() const { return {a_, b_}; }
  WheelSpeeds wheel_speeds() const { return {a_, b_}; }
  /// No NaN or infinity in it (the simulator refuses commands that have one).
  bool is_finite() const;

 private:
  Command(Kind kind, double a, double b) : kind_(kind), a_(a), b_(b) {}
  Kind kind_;
  double a_;
  double b_;
};

inline constexpr EnumName<Command::Kind> kCommandKindNames[]{
    {Command::Kind::Velocity, "velocity"},
    {Command::Kind::Unicycle, "unicycle"},
    {Command::Kind::Wheels, "wheels"},
    {Command::Kind::GoalReached, "goal_reached"},
    {Command::Kind::Stuck, "stuck"}};
constexpr std::span<const EnumName<Command::Kind>> enum_names(Command::Kind) {
  return kCommandKindNames;
}

/// A command with the controller's mode (an index into Controller::mode_names()) and, when a
/// transition fired at this step, the index of its guard (into guard_names(); -1: none). The
/// simulator logs a transition when the mode changes or a guard is given.
struct Decision {
  Decision(Command c, int mode_ = 0, int guard_ = -1)  // NOLINT: a Command is a Decision
      : command(c), mode(mode_), guard(guard_) {}
  Command command;
  int mode;
  int guard;
};

/// A robot's decision-maker, called once per step. One instance per robot; it may keep state.
/// Exceptions thrown by decide() end the simulation and reach the caller (the built-in kinds
/// never throw).
class Controller {
 public:
  /// `mode_names` name the modes decide() reports (the CSV's mode column, the summary's
  /// mode_time); `guard_names` the guards it reports.
  explicit Controller(std::vector<std::string> mode_names = {"drive"},
                      std::vector<std::string> guard_names = {});
  virtual ~Controller() = default;
  Controller(const Controller&) = delete;
  Controller& operator=(const Controller&) = delete;

  /// One step: what to do given what the robot sees.
  virtual Decision decide(const Observation& obs) = 0;
  /// Forget everything: a run, or the next goal of the route, begins.
  virtual void reset() {}
  /// The mode the controller is in now (after reset(): the mode it starts in).
  virtual int mode() const { return 0; }

  const std::vector<std::string>& mode_names() const { return mode_names_; }
  const std::vector<std::string>& guard_names() const { return guard_names_; }

 private:
  std::vector<std::string> mode_names_;
  std::vector<std::string> guard_names_;
};

/// What a controller factory is told about the robot it makes a controller for.
struct ControllerContext {
  const RobotSpec& robot;
  const NavigationParams& params;  ///< the chapter's keys of the robot's controller section
  std::string_view robot_name;
  std::size_t robot_index{0};  ///< in the fleet (0 for a lone robot)
  /// The map known in advance (the simulator passes its world), for planners that plan on one
  /// (controller.planner.map: known); nullptr when there is none. Reactive kinds ignore it.
  const World* map{nullptr};
  /// The run's seed (sim.seed; a fleet's robot_seed of it), for controllers that sample (the
  /// rrt_connect planner): same scenario and seed, the same decisions.
  std::uint64_t seed{1};
};

/// Makes one controller per robot (fleets call it once for each robot).
using ControllerFactory = std::function<std::unique_ptr<Controller>(const ControllerContext&)>;

/// A controller from a plain function of the observation (one mode, called `mode_name`).
ControllerFactory make_controller(std::function<Command(const Observation&)> decide,
                                  std::string mode_name = "drive");

/// A robot's `controller:` section: which controller, and the parameters of each layer in its
/// own type. `params` also holds what the simulator itself reads for any controller: the
/// pipeline's cruise speed v0, heading PID and slow_when_turning for velocity commands, and
/// obstacle_memory for the observation. The planner, robot avoidance and the safety layer wrap
/// every controller, a user's too (ControllerMaker, the simulator).
struct ControllerConfig {
  /// A built-in kind (nav/controller_registry.hpp), or the name of a user's controller.
  std::string kind{"hybrid"};
  NavigationParams params{};         ///< the chapter's keys, at the section's top level
  RobotAvoidanceParams avoidance{};  ///< robot_avoidance, avoidance_*: robot_avoidance.hpp
  PlannerParams planner{};           ///< `planner:` (planner_controller.hpp; kind none: off)
  DwaParams dwa{};                   ///< `dwa:`, read by the dwa kind
  SafetyParams safety{};             ///< `safety:` (safety_layer.hpp), on by default
  /// A user's controller; empty: the built-in kind named by `kind`.
  ControllerFactory factory;

  bool is_builtin() const { return !factory; }

  /// The section's keys, `kind` and `preset` aside (those name things: the scenario reader reads
  /// them first).
  template <class Fields>
  static void fields(Fields& f) {
    using C = ControllerConfig;
    f.flatten(&C::params);
    f.flatten(&C::avoidance);
    f.section("planner", &C::planner);
    f.section("dwa", &C::dwa);
    f.section("safety", &C::safety);
  }
};

}  // namespace floornav
