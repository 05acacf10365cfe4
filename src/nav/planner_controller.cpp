#include "floornav/nav/planner_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/kinematics/differential_drive.hpp"
#include "floornav/nav/heading_tracker.hpp"
#include "floornav/nav/navigation_automaton.hpp"
#include "floornav/planning/free_cells.hpp"
#include "floornav/planning/line_of_sight.hpp"
#include "floornav/planning/string_pulling.hpp"
#include "floornav/sensing/obstacle_memory.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

namespace {
constexpr double kNever = -1e300;
// Remembered points handed to the automaton per step, at most (the nearest cells come first in
// a small radius, so this is far more than a ring of IR sensors needs).
constexpr std::size_t kMaxRemembered = 1024;
// A segment of a known-map path may come this much closer than the planning radius (rounding of
// the clearance queries; the raster already judged the cells).
constexpr double kClearanceTolerance = 1e-3;  // m

std::vector<std::string> with(std::vector<std::string> names,
                              std::initializer_list<const char*> more) {
  for (const char* m : more) names.emplace_back(m);
  return names;
}

// No obstacle within `r` of the segment a-b, by sphere tracing the world's clearance (exact,
// 1-Lipschitz: a query answering c clears the next c metres).
bool segment_clear(const World& world, const Vec2& a, const Vec2& b, double r) {
  const Vec2 d = b - a;
  const double len = d.norm();
  double s = 0.0;
  for (int k = 0; k < 100000; ++k) {
    const Vec2 p = len > 0.0 ? Vec2(a + d * (s / len)) : a;
    const double c = world.clearance(p) - r;
    if (!(c >= kClearanceTolerance)) return false;
    if (s >= len) return true;
    s = std::min(len, s + c);
  }
  return false;
}

bool same_frame(const RasterFrame& a, const RasterFrame& b) {
  return a.origin.position == b.origin.position && a.origin.theta == b.origin.theta &&
         a.cell == b.cell && a.width == b.width && a.height == b.height;
}
}  // namespace

std::shared_ptr<const KnownMapRaster> KnownMapRasters::get(const World& world, double radius,
                                                           double cell, const Vec2& from,
                                                           const Vec2& goal) {
  RasterOptions options;
  if (cell > 0.0) {  // as given (planner.cell_size), not made finer for small robots
    options.cell_size = cell;
    options.cell_finer_than_radius = false;
  }
  const Vec2 goals[] = {goal};
  const auto frame = choose_raster_frame(world, radius, from, goals, options);
  if (!frame) return nullptr;
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const Entry& e : entries_)
    if (e.world == &world && e.raster->radius == radius && same_frame(e.raster->frame, *frame))
      return e.raster;
  auto built = std::make_shared<KnownMapRaster>();
  built->frame = *frame;
  built->radius = radius;
  built->raster = free_cells(world, radius, *frame);
  entries_.push_back({&world, built});
  return built;
}

PlannerController::PlannerController(Setup setup)
    : Controller(with(setup.inner->mode_names(), {"recovery_back_up", "recovery_turn", "stuck"}),
                 with(setup.inner->guard_names(), {"progress_stalled", "no_path", "recovered"})),
      inner_(std::move(setup.inner)),
      nav_(setup.params),
      p_(setup.planner),
      robot_(setup.robot),
      map_(setup.map),
      rasters_(setup.rasters ? setup.rasters : std::make_shared<KnownMapRasters>()),
      seed_(setup.seed),
      rrt_connect_(rrt_connect_search()),
      progress_(setup.planner.progress_window, 0.0) {
  if (!robot_) throw std::invalid_argument("planner: no robot");
  // rrt_connect_path's precondition, checked here so that a plan in the step loop never throws.
  if (p_.max_samples > kMaxRrtConnectSamples)
    throw std::invalid_argument("planner.max_samples " + std::to_string(p_.max_samples) +
                                " is above the limit of " + std::to_string(kMaxRrtConnectSamples));
  if (p_.kind == PlannerKind::RrtConnect && !rrt_connect_)
    throw InputError("", "controller.planner.kind", kNoRrtConnect);
  if (p_.map == PlannerMap::Known && !map_)
    throw std::invalid_argument("planner.map is 'known', but no map was given to the planner");
  inner_modes_ = static_cast<int>(inner_->mode_names().size());
  inner_guards_ = static_cast<int>(inner_->guard_names().size());
  for (const std::string& name : inner_->mode_names())
    holds_subgoal_.push_back(name == mode_names::kFollowCw || name == mode_names::kFollowCcw ||
                             name == mode_names::kAvoidObstacle);
  const double r = robot_->body_radius;
  radius_ = p_.radius > 0.0 ? p_.radius : r;
  lookahead_ = p_.lookahead > 0.0 ? p_.lookahead : 6.0 * r;
  corner_ = 0.5 * lookahead_;
  progress_distance_ = p_.progress_distance > 0.0 ? p_.progress_distance : r;
  backup_distance_ = p_.backup_distance > 0.0 ? p_.backup_distance : r;
  progress_ = ProgressChecker(p_.progress_window, progress_distance_);
  if (p_.map == PlannerMap::Sensed || p_.memory_range > 0.0) {
    const double window = p_.window > 0.0 ? p_.window : p_.map == PlannerMap::Sensed ? 20.0 : 4.0;
    // At most 2000 cells across (validate_scenario refuses finer explicit cells).
    const double cell =
        std::max(p_.cell_size > 0.0 ? p_.cell_size : radius_ / 3.0, window / 2000.0);
    grid_.emplace(cell, std::max(4, static_cast<int>(std::ceil(window / cell))), p_.decay);
  }
  points_.resize(robot_->sensors.size() + ObstacleMemory::kCapacity + kMaxRemembered);
  if (p_.guard_horizon > 0.0) {
    std::vector<Vec2> footprint = robot_->footprint;
    if (footprint.size() < 3) {  // a disc robot: the 16-gon around its body disc
      constexpr int kSides = 16;
      const double R = r / std::cos(kPi / kSides);
      for (int k = 0; k < kSides; ++k)
        footprint.emplace_back(R * std::cos(2.0 * kPi * k / kSides),
                               R * std::sin(2.0 * kPi * k / kSides));
    }
    FootprintGuardParams gp;
    gp.horizon = p_.guard_horizon;
    gp.margin = p_.guard_margin;
    gp.turn_rate = std::min(1.0, 0.5 * max_turn_rate(robot_->drive));
    gp.back_speed = 0.25 * nav_.v0;
    guard_.emplace(std::move(footprint), gp);
    remembered_.resize(4 * kMaxRemembered);
  }
  reset();
}

void PlannerController::reset() {
  inner_->reset();
  phase_ = Phase::Follow;
  planned_ = false;
  replan_now_ = false;
  path_.clear();
  tail_ = 0.0;
  recoveries_ = 0;
  subgoal_held_ = false;
  last_plan_time_ = kNever;
  searches_ = 0;
  pid_ = {};
  turn_sign_ = 0;
  mode_ = inner_->mode();
}

bool PlannerController::search_cells(const FreeRaster& raster, const RasterFrame& f, GridCell s,
                                     GridCell g) {
  if (p_.kind == PlannerKind::RrtConnect) {
    // One stream per search (the run's seed and the search's index): the same run, the same
    // samples, whatever thread it runs on.
    const std::uint64_t seed = seed_ * 0x100000001b3ULL + ++searches_;
    if (!rrt_connect_(raster, s, g, seed, p_.max_samples, samples_)) return false;
    for (const Vec2& q : samples_) polyline_.push_back(f.to_world(q));
    return true;
  }
  if (!search_.search(raster, s, g, cells_)) return false;
  for (const GridCell& c : cells_.cells)
    polyline_.push_back(f.to_world(Vec2(c.x + 0.5, c.y + 0.5)));
  return true;
}

int PlannerController::own_mode(Phase p) const {
  switch (p) {
    case Phase::BackUp:
      return inner_modes_;
    case Phase::Turn:
      return inner_modes_ + 1;
    case Phase::Stuck:
      return inner_modes_ + 2;
    case Phase::Follow:
      break;
  }
  return inner_->mode();
}

Decision PlannerController::decide(const Observation& obs) {
  if (obs.t < last_t_ && grid_) grid_->clear();  // a new run with the same controller
  last_t_ = obs.t;
  const Vec2 x = obs.pose.position;
  if (grid_) {
    grid_->follow(x);
    const double reach = p_.sense_range > 0.0 ? p_.sense_range : 1e9;
    grid_->update(obs.beams, obs.ranges, robot_->sensors, reach, obs.t);
  }
  if (phase_ == Phase::Stuck) return {Command::stuck(), mode_};
  if (obs.goal_distance() < nav_.epsilon) return {Command::goal_reached(), mode_};
  if (!guard_) return phase_ != Phase::Follow ? recover(obs) : follow(obs);
  guard_points(obs);
  return guarded(obs, phase_ != Phase::Follow ? recover(obs) : follow(obs));
}

void PlannerController::guard_points(const Observation& obs) {
  guard_->set_points(obs.pose, obs.points, max_forward_speed(robot_->drive));
  if (!grid_) return;
  // The rolling grid remembers what the sensors do not see now (a lidar's blind sector behind).
  const std::size_t n = grid_->remembered_points(obs.pose.position, guard_->keep_radius(), obs.t,
                                                 std::span<Vec2>(remembered_));
  guard_->add_points(std::span<const Vec2>(remembered_.data(), n));
}

Decision PlannerController::guarded(const Observation& obs, Decision d) {
  const Command& c = d.command;
  UnicycleCommand wanted;
  switch (c.kind()) {
    case Command::Kind::Velocity:  // the pipeline of Fig 5.12, as the simulator runs it
      wanted = track_velocity(c.u(), obs.pose.theta, nav_.v0, nav_.heading_pid, pid_, obs.dt,
                              nav_.slow_when_turning);
      break;
    case Command::Kind::Unicycle:
      wanted = c.unicycle_command();
      break;
    case Command::Kind::Wheels:
      wanted = wheels_to_unicycle(robot_->drive, c.wheel_speeds());
      break;
    default:
      return d;
  }
  // What the wheels will drive (saturation keeps omega, sheds V).
  const UnicycleCommand driven =
      wheels_to_unicycle(robot_->drive, saturate_wheels(robot_->drive, wanted));
  const GuardResult r = guard_->check(driven.v, driven.omega);
  if (r.replaced)
    ++guard_replaced_;
  else if (r.scale < 1.0)
    ++guard_slowed_;
  d.command = Command::unicycle(r.v, r.omega);
  return d;
}

bool PlannerController::guard_blocks(double v, double omega) const {
  return guard_->free_fraction(v, omega) < guard_->params().min_scale;
}

bool PlannerController::plan(const Vec2& from, const Vec2& goal, double t) {
  ++plans_;
  last_plan_time_ = t;
  const bool had_path = planned_;
  replan_now_ = false;
  planned_ = p_.map == PlannerMap::Known ? plan_known(from, goal) : plan_sensed(from, goal, t);
  if (!planned_) {
    path_.clear();
    return false;
  }
  path_.assign(pulled_);
  path_.project(from, lookahead_);
  const double left = path_.remaining() + tail_;
  // A new plan that is longer (the way turned out to be blocked) is no progress: if the robot
  // does not make up for it within the window, that is a stall like any other.
  if (!had_path) progress_.reset(t, left);
  subgoal_held_ = false;
  return true;
}

bool PlannerController::plan_known(const Vec2& from, const Vec2& goal) {
  tail_ = 0.0;
  const double r_plan = radius_ + p_.inflation;
  if (!known_ || !map_->bounds()) known_ = rasters_->get(*map_, r_plan, p_.cell_size, from, goal);
  if (!known_) {  // a map too large to rasterise: the automaton alone, straight for the goal
    pulled_.assign({from, goal});
    return true;
  }
  const RasterFrame& f = known_->frame;
  auto attempt = [&](const FreeRaster& raster, double r) {
    const double snap = r / f.cell + 2.0;
    const auto s = snap_to_free(raster, f.to_cells(from), snap);
    const auto g = snap_to_free(raster, f.to_cells(goal), snap);
    if (!s || !g) return false;
    polyline_.clear();
    polyline_.push_back(from);
    if (!search_cells(raster, f, *s, *g)) return false;
    polyline_.push_back(goal);
    pull_string(
        polyline_, [&](const Vec2& a, const Vec2& b) { return segment_clear(*map_, a, b, r); },
        pulled_);
    return true;
  };
  if (attempt(known_->raster, r_plan)) return true;
  if (p_.inflation <= 0.0) return false;
  // No path with the margin: perhaps there is one for the radius alone.
  raster_ = free_cells(*map_, radius_, f);
  return attempt(raster_, radius_);
}

bool PlannerController::plan_sensed(const Vec2& from, const Vec2& goal, double t) {
  const RollingGrid& grid = *grid_;
  const double c = grid.cell();
  const GridCell o = grid.origin();
  const RasterFrame f{Pose2{Vec2(o.x * c, o.y * c), 0.0}, c, grid.side(), grid.side()};
  // A goal beyond the window: plan to the nearest point inside it, the rest is a straight tail.
  const Vec2 lo = f.origin.position + Vec2(c, c);
  const Vec2 hi = f.origin.position + Vec2((grid.side() - 1) * c, (grid.side() - 1) * c);
  plan_goal_ = goal.cwiseMax(lo).cwiseMin(hi);
  tail_ = (goal - plan_goal_).norm();
  auto attempt = [&](double r) {
    grid.inflate(r, t, raster_);
    const double snap = r / c + 2.0;
    const auto s = snap_to_free(raster_, f.to_cells(from), snap);
    const auto g = snap_to_free(raster_, f.to_cells(plan_goal_), snap);
    if (!s || !g) return false;
    polyline_.clear();
    polyline_.push_back(from);
    if (!search_cells(raster_, f, *s, *g)) return false;
    polyline_.push_back(plan_goal_);
    // A robot standing in an inflated cell sees nothing from where it is: the sight lines start
    // at the free cell it snapped to instead, or the path would keep every cell of the octile
    // path near it and the subgoal would be a cell away (reached at once, again and again).
    const Vec2 at = f.to_cells(from);
    const bool inside = !raster_.is_free(static_cast<int>(std::floor(at.x())),
                                         static_cast<int>(std::floor(at.y())));
    const Vec2 sight_from = inside ? Vec2(s->x + 0.5, s->y + 0.5) : at;
    pull_string(
        polyline_,
        [&](const Vec2& a, const Vec2& b) {
          return line_of_sight(raster_, a == from ? sight_from : f.to_cells(a), f.to_cells(b));
        },
        pulled_);
    return true;
  };
  return attempt(radius_ + p_.inflation) || (p_.inflation > 0.0 && attempt(radius_));
}

bool PlannerController::sensed_path_clear(const Vec2& x, double t) {
  const RollingGrid& grid = *grid_;
  const double c = grid.cell();
  const GridCell o = grid.origin();
  const RasterFrame f{Pose2{Vec2(o.x * c, o.y * c), 0.0}, c, grid.side(), grid.side()};
  grid.inflate(radius_ + p_.inflation, t, raster_);
  const auto points = path_.points();
  Vec2 from = x;
  for (std::size_t i = path_.segment() + 1; i < points.size(); ++i) {
    if (!line_of_sight(raster_, f.to_cells(from), f.to_cells(points[i]))) return false;
    from = points[i];
  }
  return true;
}

std::span<const Vec2> PlannerController::points_with_memory(const Observation& obs) {
  if (!grid_ || !(p_.memory_range > 0.0)) return obs.points;
  const std::size_t n = std::min(obs.points.size(), points_.size());
  std::copy(obs.points.begin(), obs.points.begin() + static_cast<std::ptrdiff_t>(n),
            points_.begin());
  const std::size_t m =
      grid_->remembered_points(obs.pose.position, robot_->body_radius + p_.memory_range, obs.t,
                               std::span<Vec2>(points_.data() + n, points_.size() - n));
  return std::span<const Vec2>(points_.data(), n + m);
}

Decision PlannerController::follow(const Observation& obs) {
  const Vec2 x = obs.pose.position;
  bool replan = !planned_ || replan_now_;
  if (planned_ && p_.map == PlannerMap::Sensed && obs.t - last_plan_time_ >= p_.replan_period) {
    // A sampling planner draws a new, different path every time: replanning a path that is
    // still clear would move the subgoal about and the robot would dither. Keep it.
    if (p_.kind == PlannerKind::RrtConnect && sensed_path_clear(x, obs.t))
      last_plan_time_ = obs.t;
    else
      replan = true;
  }
  if (planned_ && path_.project(x, lookahead_ + corner_) > std::max(lookahead_, 4.0 * radius_))
    replan = true;  // strayed from the path (a long boundary-following episode)
  if (replan && !plan(x, obs.goal, obs.t)) {
    if (p_.map == PlannerMap::Known) return give_up(inner_guards_ + 1);  // nothing will change
    return begin_recovery(obs, inner_guards_ + 1);
  }
  const double before = progress_.anchor_time();
  if (progress_.stalled(obs.t, path_.remaining() + tail_))
    return begin_recovery(obs, inner_guards_);
  if (progress_.anchor_time() != before) recoveries_ = 0;  // progress: a fresh budget

  if (!subgoal_held_) {
    subgoal_ = path_.subgoal(x, lookahead_, corner_);
    // On the sensed map a robot in a narrow pocket keeps the octile path's cells near it (no
    // sight line past them), and the subgoal may be a cell away: the inner controller would
    // call it reached at once, again after every replan, and stand still. Then the point
    // `lookahead` along the path instead.
    const double reached = std::min(nav_.epsilon, 0.5 * robot_->body_radius);
    if (p_.map == PlannerMap::Sensed && (subgoal_ - x).norm() < 2.0 * reached)
      subgoal_ = path_.point_at(path_.length() - path_.remaining() + lookahead_);
  }
  Observation in = obs;
  in.goal = subgoal_;
  in.points = points_with_memory(obs);
  Decision d = inner_->decide(in);
  if (d.command.kind() == Command::Kind::GoalReached) {
    // The inner controller reached the subgoal (the end of a path short of the goal, or a held
    // subgoal): let go of it and plan on.
    inner_->reset();
    subgoal_held_ = false;
    last_plan_time_ = kNever;
    // Plan again at once, but as a replan: a fresh start would reset the progress checker, and
    // a subgoal reached again and again where the robot stands would never count as a stall.
    replan_now_ = true;
    mode_ = inner_->mode();
    return {Command::unicycle(0.0, 0.0), mode_, d.guard};
  }
  if (d.command.kind() == Command::Kind::Stuck) return give_up(d.guard);
  subgoal_held_ =
      d.mode >= 0 && d.mode < inner_modes_ && holds_subgoal_[static_cast<std::size_t>(d.mode)];
  mode_ = d.mode;
  return d;
}

Decision PlannerController::begin_recovery(const Observation& obs, int guard) {
  progress_.reset(obs.t, path_.remaining() + tail_);
  if (recoveries_ >= p_.max_recoveries) return give_up(guard);
  ++recoveries_;
  ++recoveries_total_;
  phase_ = Phase::BackUp;
  phase_start_ = obs.t;
  phase_pose_ = obs.pose;
  mode_ = own_mode(phase_);
  return {Command::unicycle(-0.5 * nav_.v0, 0.0), mode_, guard};
}

Decision PlannerController::give_up(int guard) {
  phase_ = Phase::Stuck;
  mode_ = own_mode(phase_);
  return {Command::stuck(), mode_, guard};
}

Decision PlannerController::recover(const Observation& obs) {
  const Vec2 x = obs.pose.position;
  const double v_back = 0.5 * nav_.v0;
  if (phase_ == Phase::BackUp) {
    const Vec2 h = obs.pose.heading();
    bool blocked = false;  // something right behind: backing further would hit it
    if (guard_) {
      blocked = guard_blocks(-v_back, 0.0);
    } else {
      const double near = robot_->body_radius + std::max(nav_.d_unsafe, 0.02);
      for (const Vec2& q : obs.points)
        if ((q - x).dot(h) < 0.0 && (q - x).squaredNorm() < near * near) blocked = true;
    }
    const bool done = (x - phase_pose_.position).norm() >= backup_distance_ ||
                      obs.t - phase_start_ >= backup_distance_ / v_back + 1.0;
    if (!blocked && !done) return {Command::unicycle(-v_back, 0.0), mode_};
    // Backed up: plan again from here and turn towards the new path.
    plan(x, obs.goal, obs.t);
    const Vec2 towards = (planned_ ? path_.subgoal(x, lookahead_, corner_) : obs.goal) - x;
    const double want = towards.squaredNorm() > 0.0
                            ? wrap_angle(std::atan2(towards.y(), towards.x()) - obs.pose.theta)
                            : 0.0;
    turn_target_ =
        wrap_angle(obs.pose.theta + std::clamp(want, -p_.recovery_turn, p_.recovery_turn));
    phase_ = Phase::Turn;
    phase_start_ = obs.t;
    turn_sign_ = 0;
    mode_ = own_mode(phase_);
  }
  const double omega = std::min(1.0, 0.5 * max_turn_rate(robot_->drive));
  const double err = wrap_angle(turn_target_ - obs.pose.theta);
  // The long way round (the short one blocked) may take up to a whole turn.
  const double limit = (turn_sign_ != 0 ? 2.0 * kPi : p_.recovery_turn) / omega + 1.0;
  if (std::abs(err) > 0.1 && obs.t - phase_start_ < limit) {
    int dir = turn_sign_ != 0 ? turn_sign_ : (err > 0.0 ? 1 : -1);
    if (guard_ && guard_blocks(0.0, dir * omega)) {
      // A corner would swing into a point: round the other way, once; both blocked: done.
      dir = turn_sign_ == 0 ? -dir : 0;
      turn_sign_ = dir;
      if (dir != 0 && guard_blocks(0.0, dir * omega)) dir = 0;
    }
    if (dir != 0) return {Command::unicycle(0.0, dir * omega), mode_};
  }
  // Recovered: follow the (new) path again.
  turn_sign_ = 0;
  phase_ = Phase::Follow;
  inner_->reset();
  subgoal_held_ = false;
  if (!planned_) last_plan_time_ = kNever;
  progress_.reset(obs.t, path_.remaining() + tail_);
  Decision d = follow(obs);
  if (d.guard < 0 && phase_ == Phase::Follow) d.guard = inner_guards_ + 2;
  return d;
}

}  // namespace floornav
