#include "floornav/nav/dwa_controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "floornav/geometry/angle.hpp"
#include "floornav/kinematics/unicycle.hpp"
#include "floornav/nav/navigation_automaton.hpp"
#include "floornav/world/lower_envelope.hpp"

namespace floornav {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// Felzenszwalb & Huttenlocher's exact 1-D squared distance transform: d[q] = min_p (q - p)^2 +
// f[p] over the finite f[p] (infinity when there is none). v and z are scratch (n and n + 1).
void edt_1d(const double* f, double* d, int n, int* v, double* z) {
  const auto is_site = [f](int q) { return f[q] != kInf; };
  const auto intersect = [f](int p, int q) {
    return ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p));
  };
  const auto emit = [f, d](int q, int p) {
    const double dq = q - p;
    d[q] = dq * dq + f[p];
  };
  if (!envelope_detail::lower_envelope(n, is_site, intersect, emit, v, z))
    std::fill(d, d + n, kInf);
}
}  // namespace

double dwa_footprint_discs(std::span<const Vec2> footprint) {
  if (footprint.size() < 3) return 1.0;
  Vec2 lo = footprint[0], hi = footprint[0];
  for (const Vec2& q : footprint) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  const Vec2 size = hi - lo;
  const double length = std::max(size.x(), size.y()), width = std::min(size.x(), size.y());
  return std::max(1.0, std::ceil(length / std::max(width, 1e-9)));
}

double dwa_roll_out_poses(const DwaParams& p) {
  return std::max(1.0, std::ceil(p.horizon / p.sim_step));
}

double dwa_score(const DwaParams& p, double heading_error, double dist, double v, double v_max) {
  const double heading = 1.0 - std::abs(wrap_angle(heading_error)) / kPi;
  const double clearance = std::min(dist, p.max_clearance) / p.max_clearance;
  const double velocity = v_max > 0.0 ? v / v_max : 0.0;
  return p.heading * heading + p.clearance * clearance + p.velocity * velocity;
}

DwaController::DwaController(const NavigationParams& params, const DwaParams& dwa,
                             const RobotSpec& robot)
    : Controller({"dwa", "dwa_brake", mode_names::kStop}), nav_(params), p_(dwa), robot_(&robot) {
  const DiffDriveParams& d = robot.drive;
  v_max_ = std::min(params.v0, max_forward_speed(d));
  w_max_ = max_turn_rate(d);
  const double r = robot.body_radius;
  range_ = p_.range > 0.0 ? p_.range : v_max_ * p_.horizon + 4.0 * r;
  // Cells of a fifth of the body radius, coarser when the map would exceed 1000 cells across.
  cell_ = std::max(std::clamp(r / 5.0, 0.01, 0.05), 2.0 * range_ / 1000.0);
  side_ = std::max(4, static_cast<int>(std::ceil(2.0 * range_ / cell_)));
  const std::size_t n = static_cast<std::size_t>(side_) * static_cast<std::size_t>(side_);
  dist2_.assign(n, kInf);
  f_.assign(static_cast<std::size_t>(side_), kInf);
  d_.assign(static_cast<std::size_t>(side_), kInf);
  z_.assign(static_cast<std::size_t>(side_) + 2, 0.0);
  v_idx_.assign(static_cast<std::size_t>(side_) + 1, 0);
  // Discs covering the footprint: k along its long side, each round its share of the box.
  const double count = dwa_footprint_discs(robot.footprint);
  if (count > kMaxDwaFootprintDiscs)  // validate_scenario refuses it first, with the key
    throw std::invalid_argument("dwa: the footprint needs more than 64 discs to cover");
  if (robot.footprint.size() >= 3) {
    Vec2 lo = robot.footprint[0], hi = robot.footprint[0];
    for (const Vec2& q : robot.footprint) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
    const Vec2 size = hi - lo;
    const bool along_x = size.x() >= size.y();
    const double length = along_x ? size.x() : size.y(), width = along_x ? size.y() : size.x();
    const int k = static_cast<int>(count);
    const double piece = length / k;
    const double radius = std::hypot(0.5 * piece, 0.5 * width);
    for (int i = 0; i < k; ++i) {
      const double a = (along_x ? lo.x() : lo.y()) + (i + 0.5) * piece;
      const double b = along_x ? 0.5 * (lo.y() + hi.y()) : 0.5 * (lo.x() + hi.x());
      discs_.push_back({along_x ? Vec2(a, b) : Vec2(b, a), radius});
    }
  } else {
    discs_.push_back({Vec2::Zero(), r});
  }
}

void DwaController::reset() {
  v_ = 0.0;
  w_ = 0.0;
  mode_ = 0;
}

void DwaController::build_distance_map(const Vec2& centre, std::span<const Vec2> points) {
  origin_ = centre - Vec2(range_, range_);
  std::fill(dist2_.begin(), dist2_.end(), kInf);
  any_obstacle_ = false;
  const std::size_t s = static_cast<std::size_t>(side_);
  for (const Vec2& q : points) {
    const Vec2 c = (q - origin_) / cell_;
    const int ix = static_cast<int>(std::floor(c.x())), iy = static_cast<int>(std::floor(c.y()));
    if (ix < 0 || iy < 0 || ix >= side_ || iy >= side_) continue;
    dist2_[static_cast<std::size_t>(iy) * s + static_cast<std::size_t>(ix)] = 0.0;
    any_obstacle_ = true;
  }
  if (!any_obstacle_) return;
  // Columns, then rows (separable exact transform).
  double* f = f_.data();
  double* d = d_.data();
  for (int x = 0; x < side_; ++x) {
    for (std::size_t y = 0; y < s; ++y) f[y] = dist2_[y * s + static_cast<std::size_t>(x)];
    edt_1d(f, d, side_, v_idx_.data(), z_.data());
    for (std::size_t y = 0; y < s; ++y) dist2_[y * s + static_cast<std::size_t>(x)] = d[y];
  }
  for (std::size_t y = 0; y < s; ++y) {
    double* row = dist2_.data() + y * s;
    std::copy(row, row + side_, f);
    edt_1d(f, d, side_, v_idx_.data(), z_.data());
    std::copy(d, d + side_, row);
  }
}

double DwaController::distance(const Vec2& p) const {
  if (!any_obstacle_) return kInf;
  const Vec2 c = (p - origin_) / cell_;
  const int ix = static_cast<int>(std::floor(c.x())), iy = static_cast<int>(std::floor(c.y()));
  if (ix < 0 || iy < 0 || ix >= side_ || iy >= side_) return kInf;
  const double d2 = dist2_[static_cast<std::size_t>(iy) * static_cast<std::size_t>(side_) +
                           static_cast<std::size_t>(ix)];
  // Cell centre to cell centre, less a cell's diagonal: a lower bound on the true distance
  // from p to the obstacle point.
  return std::sqrt(d2) * cell_ - std::sqrt(2.0) * cell_;
}

Decision DwaController::decide(const Observation& obs) {
  const double d_goal = obs.goal_distance();
  if (d_goal < nav_.epsilon) {
    mode_ = 2;
    return {Command::goal_reached(), mode_};
  }
  const double dt = obs.dt > 0.0 ? obs.dt : 0.05;
  const double a = robot_->max_acceleration, alpha = robot_->max_angular_acceleration;
  build_distance_map(obs.pose.position, obs.points);

  const double v_cap = std::min(v_max_, std::sqrt(2.0 * a * d_goal));
  const double v_lo = std::max(0.0, v_ - a * dt), v_hi = std::min(v_cap, v_ + a * dt);
  const double w_lo = std::max(-w_max_, w_ - alpha * dt), w_hi = std::min(w_max_, w_ + alpha * dt);
  const DiffDriveParams& drive = robot_->drive;
  const double wheel_v = drive.wheel_radius * drive.max_wheel_speed;
  const int steps = static_cast<int>(dwa_roll_out_poses(p_));

  // The footprint's clearance now: a robot already within the margin may still move away.
  auto footprint_gap = [&](const Pose2& q) {
    double gap = kInf;
    for (const Disc& disc : discs_)
      gap = std::min(gap, distance(q.transform_point(disc.centre)) - disc.radius);
    return gap;
  };
  const double gap_now = footprint_gap(obs.pose);
  double best = -kInf, best_v = 0.0, best_w = 0.0;
  const int nv = std::max(2, p_.v_samples), nw = std::max(2, p_.omega_samples);
  for (int i = 0; i < nv; ++i) {
    const double v_want = v_hi >= v_lo ? v_lo + (v_hi - v_lo) * i / (nv - 1) : v_hi;
    for (int j = 0; j < nw; ++j) {
      const double w = w_lo + (w_hi - w_lo) * j / (nw - 1);
      // The wheels give way to the turn (saturate_wheels): do not ask for more.
      const double v =
          std::max(0.0, std::min(v_want, wheel_v - std::abs(w) * 0.5 * drive.track_width));
      // Standing still would score best in front of any obstacle on the goal line (the
      // classic local minimum): a stop is only the fallback below.
      if (v < 1e-6 && std::abs(w) < 1e-6) continue;
      // Roll out until the first pose closer than the margin to an obstacle.
      double t_hit = kInf;
      for (int k = 1; k <= steps; ++k) {
        const double t = k * p_.sim_step;
        const double gap = footprint_gap(integrate_unicycle(obs.pose, {v, w}, t));
        if (gap < p_.margin && gap < gap_now) {  // too close, and closer than now
          t_hit = t;
          break;
        }
      }
      // Eq. 14: admissible only if it can brake to a stop before that pose.
      // (Poses are checked every sim_step: one more step of margin.)
      const double t_brake = std::max(v / a, std::abs(w) / alpha) + dt + p_.sim_step;
      if (t_hit <= t_brake) continue;
      // The heading is judged where the roll-out ends, but after at most a quarter turn: past
      // that, a spin on the spot would point anywhere by the end of the horizon.
      const double t_end = std::min(
          {t_hit, steps * p_.sim_step, std::abs(w) > 0.0 ? 0.5 * kPi / std::abs(w) : kInf});
      const Pose2 end = integrate_unicycle(obs.pose, {v, w}, t_end);
      const Vec2 to_goal = obs.goal - end.position;
      const double bearing = std::atan2(to_goal.y(), to_goal.x()) - end.theta;
      const double dist = t_hit == kInf ? kInf : v * t_hit;  // the paper's dist(v, omega)
      const double score = dwa_score(p_, bearing, dist, v, v_max_);
      if (score > best) {
        best = score;
        best_v = v;
        best_w = w;
      }
    }
  }
  if (best == -kInf) {  // nothing admissible: brake, and turn towards the goal
    const Vec2 to_goal = obs.goal - obs.pose.position;
    const double err = wrap_angle(std::atan2(to_goal.y(), to_goal.x()) - obs.pose.theta);
    best_v = std::max(0.0, v_ - a * dt);
    best_w = std::clamp(err > 0.0 ? w_ + alpha * dt : w_ - alpha * dt, -w_max_, w_max_);
    mode_ = 1;
  } else {
    mode_ = 0;
  }
  v_ = best_v;
  w_ = best_w;
  return {Command::unicycle(v_, w_), mode_};
}

}  // namespace floornav
