#pragma once
/// @file
/// One robot's run: its state, its controller, its metrics, and the step of simulation.hpp
/// (sense, decide, control, saturate, integrate, check, record). A Simulation drives one
/// agent; a FleetSimulation drives many over one world, passing each the other robots it may
/// see. The agent allocates nothing per step (trajectory recording and a transition log past
/// its reserve aside; a user's controller may); its scratch buffers belong to the caller, so that
/// a fleet needs one set per thread rather than one per robot.

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <memory>
#include <optional>

#include "floornav/automaton/hybrid_automaton.hpp"
#include "floornav/core/rng.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/nav/controller.hpp"
#include "floornav/nav/pid.hpp"
#include "floornav/nav/safety_layer.hpp"
#include "floornav/sensing/near_point_memory.hpp"
#include "floornav/sensing/obstacle_memory.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/sim/robot_task.hpp"
#include "floornav/sim/run_result.hpp"
#include "floornav/sim/sim_config.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

class SensorLayout;  // a sensor list's lidars and fans, found once (internal to the simulator)

/// One sensing of a robot: each sensor's beam and range, what Observation::beams and ::ranges
/// show.
struct SensorFrame {
  std::vector<SensorBeam> beams;
  std::vector<double> ranges;

  /// Holds `sensors` sensors (allocates only when growing); fit(0) empties it.
  void fit(std::size_t sensors);
};

/// Per-step working memory of the sensing stage, sized once for the most sensors any robot has.
struct SensingScratch {
  /// The last sense()'s beams and ranges, unless that sense() wrote them to a frame of the
  /// caller's (VecSimulation::keep_frames): then it is empty.
  SensorFrame frame;
  std::vector<Vec2> sensed;
  std::vector<Vec2> still;  ///< the returns that go to the obstacle memory
  std::vector<Vec2> points;
  FanScratch fan;               ///< the lidar fans' working memory
  std::size_t sensed_count{0};  ///< returns of the last sense(), in `sensed`
  /// The least (q - sensed_origin).squaredNorm() over `sensed` (NaN: unknown), sensed_origin the
  /// position they were sensed from: the safety layer's next filter reads it instead of the
  /// returns, which are out of the cache by then when many robots are stepped in turn.
  double sensed_nearest_d2{std::numeric_limits<double>::quiet_NaN()};
  Vec2 sensed_origin{Vec2::Zero()};
  std::size_t point_count{0};  ///< returns and remembered points, in `points`
  /// The other robots this robot is told of (Observation::robots), written by the fleet before
  /// the step; robot_count is 0 for a lone robot and for robots without robot avoidance.
  std::vector<NearbyRobot> robots;
  std::size_t robot_count{0};
  /// The bodies near this robot that its safety layer keeps clear of (other robots, people,
  /// forklifts), written by the fleet before the step; empty for a lone robot.
  std::vector<SafetyDisc> safety_discs;
  std::size_t safety_disc_count{0};
  std::vector<SafetyBox> safety_boxes;
  std::size_t safety_box_count{0};

  explicit SensingScratch(std::size_t sensors = 0, bool with_frame = true) {
    fit(sensors, with_frame);
  }
  /// Makes room for robots with up to `sensors` sensors (allocates only when growing);
  /// `with_frame` false leaves `frame` as it is.
  void fit(std::size_t sensors, bool with_frame = true);
};

/// A robot model that agents may share (robots of one kind then read one copy, which keeps a
/// step's working set small; see RobotModels): a body with its sensors' layout, and controller
/// parameters. Null members: the agent's task's own.
struct RobotModel {
  const RobotSpec* robot{nullptr};                    ///< equal to the task's robot
  std::shared_ptr<const SensorLayout> sensor_layout;  ///< made from robot->sensors
  const NavigationParams* params{nullptr};            ///< equal to the task's controller.params
};

/// What an agent needs to know; every reference must outlive it.
struct AgentSetup {
  const World* world{nullptr};
  const RobotTask* task{nullptr};  ///< body, start, route, controller parameters
  const SimConfig* sim{nullptr};
  std::unique_ptr<Controller> controller;  ///< made for this robot (see ControllerConfig)
  std::uint64_t seed{1};                   ///< this robot's sensor noise
  std::string name;                        ///< RunResult::scenario
  bool log_transitions{true};              ///< keep the transition log (fleets keep counts only)
  bool names{true};  ///< copy mode and guard names into the result (fleets keep one)
  /// Reserve the trajectory for t_max up front when recording (a lone robot: no reallocation in
  /// the step loop). Fleets grow it instead: most robots finish long before t_max.
  bool reserve_trajectory{true};
  RobotModel model;  ///< shared with other agents of the task's kind; empty: the task's own
};

class RobotAgent {
 public:
  explicit RobotAgent(AgentSetup setup);

  /// One step at time `time()`, sensing the world, `others` (the bodies of nearby robots and
  /// people, as discs) and `boxes` (moving rectangles: forklifts): sense() then act(). Returns
  /// false once the run has ended (then it does nothing).
  bool step(SensingScratch& scratch, std::span<const Circle> others = {},
            std::span<const OrientedBox> boxes = {}) {
    if (finished_) return false;
    sense(scratch, others, boxes);
    return act(scratch);
  }

  /// Step 1: casts the sensors at the current pose, turns the returns into world points and adds
  /// the remembered ones, into `scratch`. Once per step: it draws the sensor noise and updates
  /// the obstacle memory.
  void sense(SensingScratch& scratch, std::span<const Circle> others = {},
             std::span<const OrientedBox> boxes = {}) {
    sense(scratch, scratch.frame, others, boxes);
  }
  /// sense(), the beams and ranges written to `frame` (fitted to the robot's sensors) instead.
  void sense(SensingScratch& scratch, SensorFrame& frame, std::span<const Circle> others = {},
             std::span<const OrientedBox> boxes = {});
  /// What the controller sees, from the sensing in `scratch` (valid while scratch is unchanged).
  Observation observe(const SensingScratch& scratch) const {
    return observe(scratch, scratch.frame);
  }
  /// observe() with the beams and ranges of `frame`: none when it holds fewer than the robot's
  /// sensors (a frame that went elsewhere).
  Observation observe(const SensingScratch& scratch, const SensorFrame& frame) const;
  /// Steps 2-7 from the sensing in `scratch`. With `external`, that command drives the robot
  /// instead of the controller's (through the same pipeline and saturation), and the goal counts
  /// as reached within controller.epsilon. Throws std::domain_error for a command that is not
  /// finite, std::out_of_range for a mode or guard the controller did not name; a user
  /// controller's own exceptions pass through. Returns false once the run has ended.
  bool act(SensingScratch& scratch, const Command* external = nullptr);

  /// Ends the run as a collision with another robot at gap `gap` (<= 0).
  void collide_with_robot(double gap);
  /// Takes the gap (m) to the nearest other robot into min_clearance.
  void note_robot_gap(double gap) { result_.min_clearance = std::min(result_.min_clearance, gap); }

  bool finished() const { return finished_; }
  const Pose2& pose() const { return pose_; }
  /// m/s, world frame: the last step's displacement over dt (zero before the first step).
  const Vec2& velocity() const { return velocity_; }
  double time() const { return t_; }
  double body_radius() const { return robot_->body_radius; }
  const RobotSpec& robot() const { return *robot_; }
  const NavigationParams& params() const { return *nav_; }
  const Controller& controller() const { return *controller_; }
  /// The moving body (robot, person, forklift) last near this robot; kind None if none was.
  const BodyRef& mover() const { return mover_; }
  /// The safety layer under the controller (nullptr with `controller.safety: off`).
  const SafetyLayer* safety() const { return safety_ ? &*safety_ : nullptr; }
  /// The mode the controller reported last.
  int mode() const { return mode_; }
  std::size_t goal_index() const { return goal_index_; }
  /// The time after `steps` steps as written to the result (trajectory t, sim_time, transition
  /// and mode times): steps / (1/dt) when 1/dt is a whole number, so 60,000 steps of 0.01 s give
  /// 600 exactly, not the 600.000000000002 that adding dt up gives; else steps * dt. The clock
  /// the run itself uses (t_, for the guards, the obstacle memory, the stuck and t_max checks)
  /// still adds dt up, so that no trajectory moves.
  double recorded_time(long long steps) const {
    return steps_per_second_ > 0.0 ? static_cast<double>(steps) / steps_per_second_
                                   : static_cast<double>(steps) * sim_->dt;
  }
  const RunResult& result() const { return result_; }
  RunResult& result() { return result_; }

 private:
  // The steps of act(), in order.
  /// Step 2: the controller's command (or the caller's), checked and logged.
  Command decide(SensingScratch& scratch, const Command* external);
  /// A goal reached: the next one, or the end of the run (false then).
  bool next_goal();
  /// Steps 3 and 4: the command as the wheel speeds the drive can turn (Fig 5.12).
  WheelSpeeds control(const Command& command);
  /// Step 5 (and 7, the trajectory's row): the pose after one period; returns the distance moved.
  double integrate(const WheelSpeeds& wheels, const UnicycleCommand& driven);
  /// Step 6: collision, liveness and the time limit; false when the run ended.
  bool check(double moved);
  void finish(RunStatus status);
  /// Logs a transition of the controller at time t (mode change or a named guard).
  void log_transition(double t, int to, int guard);
  /// The nearest moving body of this step's safety scene, and when one was last near.
  void note_movers(const SensingScratch& scratch);
  /// Step 6's stuck, deadlock and livelock checks; true when the run ended.
  bool check_liveness();
  /// Step 4b: the safety layer's verdict on the command about to be driven.
  void guard(const SensingScratch& scratch, WheelSpeeds& wheels, UnicycleCommand& driven);
  /// Mapless safety's points: this step's returns and the near ones remembered.
  std::span<const Vec2> mapless_points(const SensingScratch& scratch);
  /// Appends the extra columns (SimConfig::record) of the row just recorded.
  void record_extras(const SensingScratch* scratch);
  /// Whether the run records sensor ranges at all, and at `step` (either interval's multiple).
  bool records_ranges() const {
    return sim_->record_ranges_every > 0 || sim_->record_ranges_also_every > 0;
  }
  bool records_ranges_at(int step) const {
    const auto at = [step](int every) { return every > 0 && step % every == 0; };
    return at(sim_->record_ranges_every) || at(sim_->record_ranges_also_every);
  }

  const World* world_;
  const RobotSpec* robot_;
  /// robot_->sensors' lidars and fans, found once (shared by agents of one model)
  std::shared_ptr<const SensorLayout> sensor_layout_;
  std::span<const Vec2> goals_;
  const NavigationParams* nav_;
  const SimConfig* sim_;
  std::unique_ptr<Controller> controller_;
  std::optional<SafetyLayer> safety_;
  /// The point the last safety stop met, for the next sense() (RobotAgent::guard).
  Vec2 safety_return_{Vec2::Zero()};
  bool has_safety_return_{false};
  int mode_{0};
  ChatterMonitor chatter_{};
  PidState pid_{};
  Rng rng_;
  Pose2 pose_{};
  /// goals_[min(goal_index_, size - 1)], kept beside the pose: reading it from the task's goal
  /// list every step was a cache miss per robot step in a fleet of 1,000.
  Vec2 goal_{Vec2::Zero()};
  Vec2 velocity_{Vec2::Zero()};
  double t_{0.0};
  /// rad: the heading errors to the goal summed over the steps driven (path_irregularity).
  double heading_error_sum_{0.0};
  long long wait_steps_{0};       ///< steps the body moved slower than kStillSpeed: wait_time
  double steps_per_second_{0.0};  ///< 1/dt when that is a whole number, else 0: recorded_time
  std::size_t goal_index_{0};
  bool finished_{false};
  bool use_memory_{false};
  bool log_transitions_{true};
  bool disc_body_{true};  ///< no footprint polygon: the body is the disc
  // Where the robot last moved (or came nearer its goal), when, and its goal distance then.
  Vec2 stuck_anchor_{Vec2::Zero()};
  double stuck_anchor_time_{0.0};
  double stuck_anchor_to_goal_{0.0};
  // Liveness: the nearest goal distance so far (for this goal) and when it was reached; the
  // moving body last near, and when.
  double progress_best_{0.0};
  double progress_time_{0.0};
  BodyRef mover_{};
  double mover_time_{-std::numeric_limits<double>::infinity()};
  double stuck_radius_{0.0};
  /// m: a lower bound on the body's clearance to the world at pose_ (exact right after it is
  /// computed). Disc bodies only; it lets a step skip the clearance query and the inside test.
  double clearance_bound_{0.0};
  ClearanceHint clearance_hint_;  ///< the last exact query's nearest obstacles (see World)
  /// (cos, sin) of heading_theta_, the heading the sensors last saw: the step's integration
  /// reuses them.
  Vec2 heading_{1.0, 0.0};
  double heading_theta_{std::numeric_limits<double>::quiet_NaN()};
  std::vector<long long> mode_steps_;  ///< steps spent in each mode: mode_time = steps * dt
  bool record_extras_{false};  ///< SimConfig::record asks for extra columns (and rows are kept)
  /// The last step's command, for record_extras: u (NaN unless a velocity), (V, omega) asked.
  Vec2 last_u_{Vec2::Zero()};
  UnicycleCommand last_wanted_{};
  double last_theta_{0.0};  ///< rad, the heading the command was decided at
  RunResult result_{};
  /// Last: 2.3 KB that most robots never touch (controller.obstacle_memory is off by default),
  /// kept from between the fields every step reads.
  ObstacleMemory memory_{};
  /// Mapless safety (SafetyMap::Sensed) only: the returns near the robot, for the layer to keep
  /// clear of where the sensors no longer see (RobotAgent::guard).
  std::unique_ptr<NearPointMemory> near_memory_;
  std::vector<Vec2> safety_points_;    ///< this step's returns, then the remembered ones
  std::vector<Circle> moving_bodies_;  ///< the step's moving bodies, whose returns are not kept
};

}  // namespace floornav
