#pragma once
/// @file
/// The safety layer: the execution level of the chapter's architecture, between any controller
/// (built-in, planner, DWA, a user's C++ or Python controller, an external command) and the
/// wheels. It passes a command unchanged unless driving it could bring the robot's body into its
/// protective field (SafetyParams::margin) of anything the robot knows of, and otherwise drives
/// the nearest command that cannot: the same turn at a lower speed, standing still, or, when
/// something is coming at a robot that stands, a way out.
///
/// What "could" means: the command's stopping path. The robot drives the command for one
/// control period (plus SafetyParams::reaction_time) and then brakes along the same arc at its
/// max_acceleration (a turn on the spot stops with the step); the body swept along that path
/// must keep
///   - from the world (the map the robot navigates by: walls, obstacles, the occupancy grid) and
///     from this step's range returns: the margin, or, when it is nearer already, what it has;
///   - from a body that moves on its own (a person, a forklift, a robot without this layer): the
///     margin plus as far as that body can come within one step (its top speed times the step);
///   - from another robot running this layer: half of the room between the two beyond the
///     margin, measured along the line between their centres. Each keeps to its half, so the two
///     never meet (the projection argument of reciprocal avoidance with a one-step horizon).
/// Standing still is always allowed against the world and reciprocal robots, so the layer never
/// has to choose between two contacts; against bodies that move on their own it can only be
/// the one that does not move into them (see docs/SAFETY.md).
///
/// A slow-down field (SafetyParams::slowdown_distance) caps the forward speed near anything, as
/// ISO 3691-4's warning fields and Nav2's collision monitor do; the protective field itself grows
/// with the speed through the braking distance.

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "floornav/geometry/oriented_box.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/nav/safety_params.hpp"
#include "floornav/robot/robot_spec.hpp"

namespace floornav {

class World;
struct ClearanceHint;
struct SafetyShared;
struct SafetyBlocker;

/// Which body of the floor a SafetyDisc or SafetyBox is (for reports: who held a robot up).
struct BodyRef {
  enum class Kind : std::uint8_t { None, Robot, Person, Forklift };
  Kind kind{Kind::None};
  std::uint32_t index{0};  ///< in the fleet, the people, or the forklifts
  bool operator==(const BodyRef&) const = default;
};

/// A disc body near the robot: another robot or a person, as it stands at the start of the step.
struct SafetyDisc {
  Vec2 position{Vec2::Zero()};
  double radius{0.0};
  /// m it may come towards any point within one step (its top speed x dt); 0: it stands still.
  double approach{0.0};
  /// It runs this layer too: each of the two keeps to its half of the room between them.
  bool reciprocal{false};
  double extra_margin{0.0};  ///< m added to the margin (SafetyParams::person_margin for people)
  BodyRef who{};
};

/// A rectangular body near the robot (a forklift), as it stands at the start of the step.
struct SafetyBox {
  OrientedBox box{};
  double approach{0.0};  ///< m it may come towards any point within one step
  BodyRef who{};
};

/// What the robot knows around it at one step.
struct SafetyScene {
  const World* world{nullptr};
  /// m: a lower bound on the body's clearance to the world at the pose (exact or not; the layer
  /// measures exactly only when this bound does not clear the stopping path).
  double world_clearance{0.0};
  std::span<const SafetyDisc> discs;
  std::span<const SafetyBox> boxes;
  std::span<const Vec2> points;  ///< m, world frame: this step's range returns
  /// Optional: the least (q - points_origin).squaredNorm() over `points`, found while they were
  /// fresh in the cache (NaN: unknown). Used when points_origin is the filtered pose.
  double points_nearest_d2{std::numeric_limits<double>::quiet_NaN()};
  Vec2 points_origin{Vec2::Zero()};
};

/// What the layer did with one command.
struct SafetyVerdict {
  UnicycleCommand command{};
  bool limited{false};  ///< the command was changed (slowed, stopped or replaced)
  /// The protective field met something: `blocker` is the nearest point of what bound the
  /// wanted command (world frame), as a safety scanner would report it.
  bool blocked{false};
  Vec2 blocker{Vec2::Zero()};
};

class SafetyLayer {
 public:
  /// `robot` must outlive the layer; `dt` is the control period.
  SafetyLayer(const RobotSpec& robot, const SafetyParams& params, double dt);

  /// The command to drive instead of `wanted` (a command within the wheel limits) at `pose`.
  SafetyVerdict filter(const Pose2& pose, const UnicycleCommand& wanted,
                       const SafetyScene& scene) const;

  /// The smallest slack (m) of the command's stopping path against everything in `scene`:
  /// >= 0 when the command is allowed. Exposed for tests and for controllers that want to rank
  /// their own candidates the same way.
  double slack(const Pose2& pose, const UnicycleCommand& command, const SafetyScene& scene) const;

  /// The stopping path of a command: its length (m, signed by the direction of travel) and turn
  /// (rad) from the pose, along one arc.
  UnicycleCommand stopping_path(const UnicycleCommand& command) const;

  const SafetyParams& params() const { return params_; }

  /// m of gap within which another body matters to the layer: its field (margin, person margin,
  /// slow-down distance) and twice its stopping path at top speed (its share of the room, against
  /// a body that takes none).
  double gap_reach() const;

 private:
  /// slack(), and where `blocker` is given, the nearest point of what bound it (unchanged when
  /// nothing binds; when the world bound it, only marked as the world's).
  /// One filter measures many commands from one pose, along paths a few centimetres long:
  /// `shared` keeps what they have in common (bit for bit what each would compute).
  /// With a finite `decide`, only whether the slack is >= decide matters: the measure stops as
  /// soon as it is known to be below (and then returns some value below `decide`). A slack at or
  /// above `exact_below` may be reported as any value at or above it (+infinity: exact).
  double measure(const Pose2& pose, const UnicycleCommand& command, const SafetyScene& scene,
                 SafetyBlocker* blocker, SafetyShared& shared, double decide,
                 double exact_below) const;
  /// The farthest any point of the body moves along the stopping path of `command`.
  double sweep_reach(const UnicycleCommand& path) const;
  /// The forward speed cap of the slow-down field at `pose` (+infinity when it does not apply).
  double slowdown_cap(const Pose2& pose, const SafetyScene& scene, SafetyShared& shared) const;
  /// Among a few ways out (standing, creeping forwards or back, straight or turning), the one
  /// with the largest slack: for when standing still no longer keeps the field.
  UnicycleCommand way_out(const Pose2& pose, const SafetyScene& scene, SafetyShared& shared) const;

  const RobotSpec* robot_;
  SafetyParams params_;
  double dt_;
  double body_reach_{0.0};  ///< m: the footprint's farthest point from the centre (0: disc)
};

}  // namespace floornav
