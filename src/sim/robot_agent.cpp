#include "floornav/sim/robot_agent.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/oriented_box.hpp"
#include "floornav/kinematics/unicycle.hpp"
#include "floornav/nav/heading_tracker.hpp"
#include "floornav/nav/robot_avoidance.hpp"
#include "floornav/robot/body_clearance.hpp"
#include "floornav/sensing/sensor_fans.hpp"

namespace floornav {

namespace {
// Robots with more sensors than this see enough at once; remembering points would only cost time.
constexpr std::size_t kMaxSensorsForMemory = 32;
// The transition log is reserved for this many switches, so that logging one allocates nothing
// in the step loop; a run that chatters beyond it grows the log (amortised, rare).
constexpr std::size_t kReservedTransitions = 1024;
// Mapless safety's memory of returns: kept this far beyond where they are added (a robot that
// drives farther than this from a return and then backs towards it has forgotten it), one per
// square of this side (a lidar's returns on a wall 1 m off lie 6.5 mm apart).
constexpr double kNearMemoryBeyond = 1.0;  // m
constexpr double kNearMemoryCell = 0.03;   // m
constexpr double kNearMemorySlack = 1e-3;  // m, against rounding at the edge of `add`
std::string fmt_decision_error(int mode, int guard, std::size_t modes, std::size_t guards) {
  return "the controller reported mode " + std::to_string(mode) + " and guard " +
         std::to_string(guard) + ", but names " + std::to_string(modes) + " modes and " +
         std::to_string(guards) + " guards";
}
// Slack subtracted per step from the clearance lower bound, far above the rounding of a
// clearance (~1e-15 m) or a step length, so the bound stays a true lower bound.
constexpr double kClearanceBoundSlack = 1e-9;  // m
// m/s: a robot slower than this is waiting (RunResult::wait_time).
constexpr double kStillSpeed = 0.01;
// A robot that comes this fraction of sim.stuck_radius nearer its goal has moved (liveness).
constexpr double kCreep = 0.1;
// The least (q - p).squaredNorm() over `points`, as the safety layer computes it (NaN when one
// is not a number: the layer then goes over the points itself).
double nearest_d2(std::span<const Vec2> points, const Vec2& p) {
  double least = std::numeric_limits<double>::infinity();
  bool nan = false;
  std::size_t i = 0;
#if defined(__SSE2__)
  // Two points at a time, each d2 as squaredNorm has it (dx * dx + dy * dy); the minimum does
  // not depend on the order (the d2 are never -0), and a NaN anywhere makes the result NaN.
  const __m128d px = _mm_set1_pd(p.x()), py = _mm_set1_pd(p.y());
  __m128d low = _mm_set1_pd(least), unordered = _mm_setzero_pd();
  for (; i + 1 < points.size(); i += 2) {
    const __m128d a = _mm_loadu_pd(points[i].data()), b = _mm_loadu_pd(points[i + 1].data());
    const __m128d dx = _mm_sub_pd(_mm_unpacklo_pd(a, b), px);
    const __m128d dy = _mm_sub_pd(_mm_unpackhi_pd(a, b), py);
    const __m128d d2 = _mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy));
    unordered = _mm_or_pd(unordered, _mm_cmpunord_pd(d2, d2));
    low = _mm_min_pd(d2, low);  // low when d2 is NaN, as std::min(low, d2)
  }
  nan = _mm_movemask_pd(unordered) != 0;
  least = std::min(_mm_cvtsd_f64(low), _mm_cvtsd_f64(_mm_unpackhi_pd(low, low)));
#endif
  for (; i < points.size(); ++i) {
    const double d2 = (points[i] - p).squaredNorm();
    nan |= std::isnan(d2);
    least = std::min(least, d2);
  }
  return nan ? std::numeric_limits<double>::quiet_NaN() : least;
}
}  // namespace

void SensorFrame::fit(std::size_t sensors) {
  beams.resize(sensors);
  ranges.resize(sensors);
}

void SensingScratch::fit(std::size_t sensors, bool with_frame) {
  if (with_frame && frame.beams.size() < sensors) frame.fit(sensors);
  // One more than the sensors: the point a safety stop met (RobotAgent::guard).
  if (sensed.size() > sensors) return;
  sensed.assign(sensors + 1, Vec2::Zero());
  still.assign(sensors + 1, Vec2::Zero());
  points.assign(sensors + 1 + ObstacleMemory::kCapacity, Vec2::Zero());
}

RobotAgent::RobotAgent(AgentSetup setup)
    : world_(setup.world),
      robot_(setup.model.robot ? setup.model.robot : &setup.task->robot),
      sensor_layout_(setup.model.sensor_layout
                         ? std::move(setup.model.sensor_layout)
                         : std::make_shared<const SensorLayout>(robot_->sensors)),
      goals_(setup.task->goals),
      nav_(setup.model.params ? setup.model.params : &setup.task->controller.params),
      sim_(setup.sim),
      controller_(std::move(setup.controller)),
      rng_(setup.seed),
      pose_(setup.task->start),
      log_transitions_(setup.log_transitions) {
  controller_->reset();
  mode_ = controller_->mode();
  if (const SafetyParams& safety = setup.task->controller.safety; safety.enabled)
    safety_.emplace(*robot_, safety, sim_->dt);
  if (safety_ && safety_->params().map == SafetyMap::Sensed) {
    // Added within the gap where the layer is told of every moving body (FleetSimulation's
    // safety discs and boxes): a return nearer than this on a moving body lies on one of them.
    const double add = std::max(robot_->body_radius + safety_->gap_reach() -
                                    robot_return_tolerance(*robot_) - kNearMemorySlack,
                                0.0);
    near_memory_ = std::make_unique<NearPointMemory>(add, add + kNearMemoryBeyond, kNearMemoryCell);
    safety_points_.resize(robot_->sensors.size() + 1 + NearPointMemory::kCapacity);
  }
  const std::size_t n_sensors = robot_->sensors.size();
  use_memory_ = nav_->obstacle_memory > 0.0 && n_sensors <= kMaxSensorsForMemory;
  stuck_radius_ = sim_->stuck_radius > 0.0 ? sim_->stuck_radius : robot_->body_radius;
  stuck_anchor_ = pose_.position;
  if (!goals_.empty()) goal_ = goals_.front();
  progress_best_ = (goal_ - pose_.position).norm();
  stuck_anchor_to_goal_ = goals_.empty() ? 0.0 : progress_best_;
  if (const double rate = std::round(1.0 / sim_->dt);
      rate >= 1.0 && rate <= 1e9 && std::abs(rate * sim_->dt - 1.0) < 1e-12)
    steps_per_second_ = rate;

  RunResult& r = result_;
  r.scenario = setup.name;
  if (!sim_->path_irregularity) r.path_irregularity = std::numeric_limits<double>::quiet_NaN();
  r.goal_count = static_cast<int>(goals_.size());
  if (setup.names) {
    r.mode_names = controller_->mode_names();
    r.guard_names = controller_->guard_names();
  }
  r.mode_time.assign(controller_->mode_names().size(), 0.0);
  mode_steps_.assign(r.mode_time.size(), 0);
  if (log_transitions_) {
    r.transitions.reserve(kReservedTransitions);
    r.transition_x.reserve(kReservedTransitions);
    r.transition_y.reserve(kReservedTransitions);
  }
  r.min_clearance = body_clearance(*world_, *robot_, pose_, clearance_hint_);
  disc_body_ = robot_->footprint.empty();
  clearance_bound_ = r.min_clearance;
  r.final_x = pose_.position.x();
  r.final_y = pose_.position.y();
  r.final_theta = pose_.theta;
  if (setup.reserve_trajectory && records_ranges() && n_sensors > 0) {
    // The frames of the whole run at once: no copy of megabytes of ranges as they grow (pages
    // never written are never touched).
    const double steps = std::ceil(sim_->t_max / sim_->dt);
    const auto per = [&](int every) { return every > 0 ? steps / every : 0.0; };
    const double frames =
        per(sim_->record_ranges_every) + per(sim_->record_ranges_also_every) + 2.0;
    const double values = std::min(frames * static_cast<double>(n_sensors), 2.0e7);
    r.range_steps.reserve(static_cast<std::size_t>(values) / n_sensors);
    r.ranges.reserve(static_cast<std::size_t>(values));
  }
  if (sim_->record_trajectory) {
    const double steps = std::ceil(sim_->t_max / sim_->dt) + 2.0;
    if (setup.reserve_trajectory)
      r.trajectory.reserve(static_cast<std::size_t>(std::min(steps, 2.0e6)));
    r.trajectory.push_back(
        {0.0, pose_.position.x(), pose_.position.y(), pose_.theta, 0.0, 0.0, 0.0, 0.0, mode_});
    record_extras_ = sim_->record.any();
    if (record_extras_) {
      const RecordOptions& o = sim_->record;
      auto& c = r.extra_columns;
      if (o.command) c.insert(c.end(), {"u_x", "u_y", "v_cmd", "omega_cmd"});
      if (o.heading) c.insert(c.end(), {"theta_d", "heading_error"});
      if (o.clearance) c.push_back("clearance");
      if (o.goal) c.insert(c.end(), {"goal_index", "goal_x", "goal_y"});
      if (o.ranges)
        for (std::size_t i = 0; i < n_sensors; ++i) c.push_back("range_" + std::to_string(i));
      last_u_ = Vec2(std::nan(""), std::nan(""));
      last_wanted_ = {std::nan(""), std::nan("")};
      record_extras(nullptr);  // the start: no command yet, nothing sensed yet
    }
  }
  if (goals_.empty())
    finish(RunStatus::Reached);
  else if (r.min_clearance <= 0.0) {  // touching is a collision, as in step()
    r.collided = true;
    finish(RunStatus::Collision);
  }
}

void RobotAgent::finish(RunStatus status) {
  finished_ = true;
  result_.status = status;
  result_.reached_goal = status == RunStatus::Reached;
  result_.sim_time = recorded_time(result_.steps);
  result_.safety_time = recorded_time(result_.safety_steps);
  // Each mode's time is a whole number of steps: written without the drift of adding dt up.
  for (double& m : result_.mode_time)
    m = recorded_time(static_cast<long long>(std::llround(m / sim_->dt)));
  result_.final_x = pose_.position.x();
  result_.final_y = pose_.position.y();
  result_.final_theta = pose_.theta;
  result_.chatter_episodes = chatter_.episodes;
  result_.first_chatter_time =
      chatter_.first_time < 0.0
          ? chatter_.first_time
          : recorded_time(static_cast<long long>(std::llround(chatter_.first_time / sim_->dt)));
}

void RobotAgent::log_transition(double t, int to, int guard) {
  RunResult& r = result_;
  if (log_transitions_) {
    // The log gets the recorded time of the step's end (t is the run's own clock, which the
    // chatter monitor keeps using).
    r.transitions.push_back({recorded_time(r.steps + 1), mode_, to, guard});
    r.transition_x.push_back(pose_.position.x());
    r.transition_y.push_back(pose_.position.y());
  }
  ++r.mode_switches;
  chatter_.record(t, nav_->chatter_switches, nav_->chatter_window);
}

void RobotAgent::record_extras(const SensingScratch* scratch) {
  const RecordOptions& o = sim_->record;
  std::vector<double>& v = result_.extra;
  const double nan = std::nan("");
  if (o.command) v.insert(v.end(), {last_u_.x(), last_u_.y(), last_wanted_.v, last_wanted_.omega});
  if (o.heading) {
    // eqs. 5.28 and 5.14, as the pipeline of Fig 5.12 computed them (none for a still u).
    const bool steered = std::isfinite(last_u_.x()) && last_u_.norm() > 1e-9;
    const double theta_d = steered ? std::atan2(last_u_.y(), last_u_.x()) : nan;
    v.insert(v.end(), {theta_d, steered ? wrap_angle(theta_d - last_theta_) : nan});
  }
  if (o.clearance) v.push_back(body_clearance(*world_, *robot_, pose_));
  if (o.goal && goals_.empty()) v.insert(v.end(), {nan, nan, nan});
  if (o.goal && !goals_.empty()) {
    const std::size_t g = std::min(goal_index_, goals_.size() - 1);
    v.insert(v.end(), {static_cast<double>(g), goals_[g].x(), goals_[g].y()});
  }
  if (o.ranges) {
    const std::size_t n = robot_->sensors.size();
    if (scratch == nullptr || scratch->frame.ranges.size() < n)
      v.insert(v.end(), n, nan);
    else
      v.insert(v.end(), scratch->frame.ranges.begin(),
               scratch->frame.ranges.begin() + static_cast<long>(n));
  }
}

void RobotAgent::guard(const SensingScratch& scratch, WheelSpeeds& wheels,
                       UnicycleCommand& driven) {
  SafetyScene scene;
  scene.discs = {scratch.safety_discs.data(), scratch.safety_disc_count};
  scene.boxes = {scratch.safety_boxes.data(), scratch.safety_box_count};
  if (safety_->params().map == SafetyMap::Known) {
    scene.world = world_;
    // A disc body's clearance bound is kept up to date every step; a footprint's is exact.
    scene.world_clearance = clearance_bound_;
    scene.points = {scratch.sensed.data(), scratch.sensed_count};
    scene.points_nearest_d2 = scratch.sensed_nearest_d2;
    scene.points_origin = scratch.sensed_origin;
  } else {  // mapless: what it senses, and the returns it remembers near it
    scene.points = mapless_points(scratch);
  }
  const SafetyVerdict verdict = safety_->filter(pose_, driven, scene);
  if (!verdict.limited) return;
  // What stopped the robot reaches its controller at the next step as one more return (a
  // safety scanner's), so that a controller whose sensors missed it (a corner between two IR
  // beams) turns away rather than pushing on against the field.
  if (verdict.blocked) {
    safety_return_ = verdict.blocker;
    has_safety_return_ = true;
  }
  wheels = saturate_wheels(robot_->drive, verdict.command);
  driven = wheels_to_unicycle(robot_->drive, wheels);
  // Wheels that stall below their least speed pivot the body differently: then stand still.
  if ((driven.v != verdict.command.v || driven.omega != verdict.command.omega) &&
      safety_->slack(pose_, driven, scene) < 0.0) {
    wheels = {};
    driven = {};
  }
  ++result_.safety_steps;
}

std::span<const Vec2> RobotAgent::mapless_points(const SensingScratch& scratch) {
  const std::span<const Vec2> sensed(scratch.sensed.data(), scratch.sensed_count);
  // Returns on bodies that move (robots that run, people, forklifts) are not world to keep.
  const double tolerance = robot_return_tolerance(*robot_);
  moving_bodies_.clear();
  for (std::size_t k = 0; k < scratch.safety_disc_count; ++k) {
    const SafetyDisc& d = scratch.safety_discs[k];
    if (d.reciprocal || d.approach > 0.0)
      moving_bodies_.push_back({d.position, d.radius + tolerance});
  }
  for (std::size_t k = 0; k < scratch.safety_box_count; ++k) {
    const OrientedBox& b = scratch.safety_boxes[k].box;
    moving_bodies_.push_back({b.center, b.bounding_radius() + tolerance});
  }
  const std::span<const Vec2> kept = near_memory_->update(sensed, pose_.position, moving_bodies_);
  // This step's returns as they are (a remembered square may hold an older return of it).
  std::copy(sensed.begin(), sensed.end(), safety_points_.begin());
  std::copy(kept.begin(), kept.end(), safety_points_.begin() + sensed.size());
  return {safety_points_.data(), sensed.size() + kept.size()};
}

void RobotAgent::note_movers(const SensingScratch& scratch) {
  // The nearest moving body of the safety scene (robots that run, people, forklifts).
  double nearest = std::numeric_limits<double>::infinity();
  const Vec2 p = pose_.position;
  for (std::size_t k = 0; k < scratch.safety_disc_count; ++k) {
    const SafetyDisc& d = scratch.safety_discs[k];
    if (!d.reciprocal && d.approach <= 0.0) continue;  // parked
    const double gap = (d.position - p).norm() - d.radius;
    if (gap < nearest) {
      nearest = gap;
      mover_ = d.who;
    }
  }
  for (std::size_t k = 0; k < scratch.safety_box_count; ++k) {
    const SafetyBox& b = scratch.safety_boxes[k];
    const double gap = signed_distance(b.box, p);
    if (gap < nearest) {
      nearest = gap;
      mover_ = b.who;
    }
  }
  if (nearest < std::numeric_limits<double>::infinity()) mover_time_ = t_;
}

bool RobotAgent::check_liveness() {
  RunResult& r = result_;
  // Among moving bodies: one was near within the last stuck_window.
  const bool among = t_ - mover_time_ <= sim_->stuck_window;
  const double to_goal = goals_.empty() ? 0.0 : (goal_ - pose_.position).norm();
  // A robot that keeps closing in on its goal is not stuck however slowly it goes (go-to-goal
  // slows down near the goal, eq. 5.19): coming nearer by a tenth of the radius counts as a move.
  if ((pose_.position - stuck_anchor_).norm() > stuck_radius_ ||
      to_goal < stuck_anchor_to_goal_ - kCreep * stuck_radius_) {
    stuck_anchor_ = pose_.position;
    stuck_anchor_time_ = t_;
    stuck_anchor_to_goal_ = to_goal;
  } else if (t_ - stuck_anchor_time_ >= (among ? sim_->deadlock_window : sim_->stuck_window)) {
    r.stuck_cause = among ? "deadlock" : "no_progress";
    finish(RunStatus::Stuck);
    return true;
  }
  if (goals_.empty()) return false;
  if (to_goal < progress_best_ - stuck_radius_) {
    progress_best_ = to_goal;
    progress_time_ = t_;
  } else if (among && t_ - progress_time_ >= sim_->livelock_window) {
    r.stuck_cause = "livelock";
    finish(RunStatus::Stuck);
    return true;
  }
  return false;
}

void RobotAgent::collide_with_robot(double gap) {
  note_robot_gap(gap);
  if (finished_) return;  // already stopped: the other robot drove into it
  result_.collided = true;
  finish(RunStatus::Collision);
}

void RobotAgent::sense(SensingScratch& scratch, SensorFrame& frame, std::span<const Circle> others,
                       std::span<const OrientedBox> boxes) {
  const RobotSpec& robot = *robot_;
  // The body disc is clear of every obstacle by at least clearance_bound_, so sensors mounted
  // within it start outside the obstacles: the world need not test that per ray.
  const std::size_t n_sensors = robot.sensors.size();
  if (frame.beams.size() < n_sensors) frame.fit(n_sensors);
  const std::span<SensorBeam> beams(frame.beams.data(), n_sensors);
  const std::span<double> ranges(frame.ranges.data(), n_sensors);
  heading_ = Vec2(std::cos(pose_.theta), std::sin(pose_.theta));
  heading_theta_ = pose_.theta;
  compute_sensor_beams(pose_, heading_, robot.sensors, *sensor_layout_, beams);
  const FreeDisc free{pose_.position, disc_body_ ? clearance_bound_ + robot.body_radius : 0.0};
  sense_ranges(*world_, beams, robot.sensors, *sensor_layout_, robot.sensor_noise, rng_, ranges,
               scratch.fan, free, others, boxes);
  if (records_ranges_at(result_.steps)) {
    // A step that only switched goals senses again at the same pose: that frame is replaced.
    if (!result_.range_steps.empty() && result_.range_steps.back() == result_.steps) {
      result_.range_steps.pop_back();
      result_.ranges.resize(result_.ranges.size() - n_sensors);
    }
    result_.range_steps.push_back(result_.steps);
    result_.ranges.insert(result_.ranges.end(), ranges.begin(), ranges.end());
  }
  scratch.sensed_count =
      ranges_to_points(beams, sensor_layout_->max_ranges(), ranges, scratch.sensed);
  if (has_safety_return_) {
    scratch.sensed[scratch.sensed_count++] = safety_return_;
    has_safety_return_ = false;
  }
  if (safety_) {
    scratch.sensed_origin = pose_.position;
    scratch.sensed_nearest_d2 =
        nearest_d2({scratch.sensed.data(), scratch.sensed_count}, scratch.sensed_origin);
  }
  scratch.point_count = scratch.sensed_count;
  if (use_memory_) {
    // The memory keeps the still world: the returns on robots that avoid each other by their
    // velocities (those told, still running) would be old positions of moving bodies.
    std::span<const Vec2> still(scratch.sensed.data(), scratch.sensed_count);
    if (scratch.robot_count > 0)
      still = {scratch.still.data(),
               drop_robot_points(still, {scratch.robots.data(), scratch.robot_count},
                                 robot_return_tolerance(robot), scratch.still)};
    scratch.point_count =
        memory_.update(still, t_, nav_->obstacle_memory, 0.25 * robot.body_radius, scratch.points);
  }
}

Observation RobotAgent::observe(const SensingScratch& scratch, const SensorFrame& frame) const {
  const std::size_t n_sensors =
      frame.beams.size() < robot_->sensors.size() ? 0 : robot_->sensors.size();
  Observation obs;
  obs.t = t_;
  obs.dt = sim_->dt;
  obs.pose = pose_;
  obs.goal = goal_;
  obs.goal_index = static_cast<int>(goal_index_);
  obs.goal_count = static_cast<int>(goals_.size());
  obs.ranges = std::span<const double>(frame.ranges.data(), n_sensors);
  obs.beams = std::span<const SensorBeam>(frame.beams.data(), n_sensors);
  obs.sensed = std::span<const Vec2>(scratch.sensed.data(), scratch.sensed_count);
  obs.points =
      use_memory_ ? std::span<const Vec2>(scratch.points.data(), scratch.point_count) : obs.sensed;
  obs.robots = std::span<const NearbyRobot>(scratch.robots.data(), scratch.robot_count);
  obs.velocity = velocity_;
  obs.robot = robot_;
  obs.params = nav_;
  return obs;
}

bool RobotAgent::act(SensingScratch& scratch, const Command* external) {
  if (finished_) return false;
  // 2. decide
  const Command command = decide(scratch, external);
  if (command.kind() == Command::Kind::Stuck) {  // the controller gave up
    result_.stuck_cause = "controller";
    finish(RunStatus::Stuck);
    return false;
  }
  if (command.kind() == Command::Kind::GoalReached) return next_goal();
  // 3. control (Fig 5.12), 4. saturate
  WheelSpeeds wheels = control(command);
  UnicycleCommand driven = wheels_to_unicycle(robot_->drive, wheels);
  // 4b. guard: the safety layer lets through only what can stop short of everything it knows.
  if (safety_) guard(scratch, wheels, driven);
  note_movers(scratch);
  // 5. integrate, 7. record (before the checks, so the final row is the state the run ended in)
  const double moved = integrate(wheels, driven);
  if (record_extras_) record_extras(&scratch);
  // 6. check
  return check(moved);
}

Command RobotAgent::decide(SensingScratch& scratch, const Command* external) {
  // The controller's command (a built-in kind steps its automaton here), or the caller's, for
  // which the goal counts as reached within epsilon.
  const Observation obs = observe(scratch);
  Command command = Command::goal_reached();
  if (external) {
    if (!(obs.goal_distance() < nav_->epsilon)) command = *external;
  } else {
    const Decision d = controller_->decide(obs);
    const auto modes = controller_->mode_names().size();
    if (d.mode < 0 || static_cast<std::size_t>(d.mode) >= modes ||
        d.guard >= static_cast<int>(controller_->guard_names().size()) || d.guard < -1)
      throw std::out_of_range(
          fmt_decision_error(d.mode, d.guard, modes, controller_->guard_names().size()));
    if (d.mode != mode_ || d.guard >= 0)
      log_transition(static_cast<double>(result_.steps + 1) * sim_->dt, d.mode, d.guard);
    mode_ = d.mode;
    command = d.command;
  }
  if (!command.is_finite())
    throw std::domain_error("the controller's command is not a finite number (NaN or infinity)");
  return command;
}

bool RobotAgent::next_goal() {
  // STOP: this goal is reached; go on to the next one, or end the run.
  ++result_.goals_reached;
  if (++goal_index_ >= goals_.size()) {
    finish(RunStatus::Reached);
    return false;
  }
  goal_ = goals_[goal_index_];
  progress_best_ = (goal_ - pose_.position).norm();
  progress_time_ = t_;
  stuck_anchor_to_goal_ = progress_best_;
  controller_->reset();
  mode_ = controller_->mode();
  pid_ = {};
  memory_.clear();
  return true;
}

WheelSpeeds RobotAgent::control(const Command& command) {
  const NavigationParams& nav = *nav_;
  UnicycleCommand wanted;
  switch (command.kind()) {
    case Command::Kind::Velocity:
      wanted = track_velocity(command.u(), pose_.theta, nav.v0, nav.heading_pid, pid_, sim_->dt,
                              nav.slow_when_turning);
      break;
    case Command::Kind::Unicycle:
      wanted = command.unicycle_command();
      break;
    case Command::Kind::Wheels:
    default:
      wanted = wheels_to_unicycle(robot_->drive, command.wheel_speeds());
      break;
  }
  if (record_extras_) {
    last_u_ =
        command.kind() == Command::Kind::Velocity ? command.u() : Vec2(std::nan(""), std::nan(""));
    last_wanted_ = wanted;
    last_theta_ = pose_.theta;
  }
  return saturate_wheels(robot_->drive, wanted);
}

double RobotAgent::integrate(const WheelSpeeds& wheels, const UnicycleCommand& driven) {
  const double dt = sim_->dt;
  RunResult& r = result_;
  // The sensors' cosine and sine of the heading, if they were taken at this heading.
  const bool sensed_here =
      std::bit_cast<std::uint64_t>(heading_theta_) == std::bit_cast<std::uint64_t>(pose_.theta);
  const Vec2 heading = sensed_here ? heading_ : Vec2(std::cos(pose_.theta), std::sin(pose_.theta));
  const Pose2 next = integrate_unicycle(pose_, driven, dt, heading);
  const double moved = (next.position - pose_.position).norm();
  velocity_ = (next.position - pose_.position) / dt;
  r.path_length += moved;
  // Counted in steps, like the clock: 200 steps of 0.01 s are 2 s, not 2.0000000000000013.
  if (moved < kStillSpeed * dt) r.wait_time = recorded_time(++wait_steps_);
  // Path irregularity as SocNavBench computes it (metrics/cost_functions.py, path_irregularity:
  // "the per step angle away from straight line to goal", its absolute value averaged over the
  // trajectory's samples), here over the poses the robot drove each step from, towards the goal
  // it was driving to. SEAN 2.0 names the same idea "rotations beyond the direct path's". A pose
  // on the goal itself adds atan2(0, 0) = 0. The metric only observes: nothing here feeds back.
  if (sim_->path_irregularity) {
    const Vec2 to_goal = goal_ - pose_.position;
    heading_error_sum_ += std::abs(
        std::atan2(heading.x() * to_goal.y() - heading.y() * to_goal.x(), heading.dot(to_goal)));
    r.path_irregularity = heading_error_sum_ / static_cast<double>(r.steps + 1);
  }
  pose_ = next;
  t_ += dt;
  ++r.steps;
  // Counted in steps, like the clock: a sum of dt's drifts (15.149999999999721).
  const auto m = static_cast<std::size_t>(mode_);
  r.mode_time[m] = static_cast<double>(++mode_steps_[m]) * dt;
  if (sim_->record_trajectory)
    r.trajectory.push_back({recorded_time(r.steps), pose_.position.x(), pose_.position.y(),
                            pose_.theta, driven.v, driven.omega, wheels.left, wheels.right, mode_});
  return moved;
}

bool RobotAgent::check(double moved) {
  RunResult& r = result_;
  // A disc body's clearance changes by at most the distance moved, so while that lower bound
  // stays above min_clearance the exact value could change neither min_clearance nor the
  // collision test (min_clearance >= 0 while running): it is computed only when it might.
  clearance_bound_ -= moved + kClearanceBoundSlack;
  if (!disc_body_ || clearance_bound_ <= r.min_clearance) {
    const double clearance = body_clearance(*world_, *robot_, pose_, clearance_hint_);
    clearance_bound_ = clearance;
    r.min_clearance = std::min(r.min_clearance, clearance);
    if (clearance <= 0.0) {
      r.collided = true;
      finish(RunStatus::Collision);
      return false;
    }
  }
  if (check_liveness()) return false;
  if (t_ >= sim_->t_max - 1e-9) {
    finish(RunStatus::Timeout);
    return false;
  }
  return true;
}

}  // namespace floornav
