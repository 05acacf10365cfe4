#include "floornav/nav/robot_avoidance.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "floornav/geometry/angle.hpp"
#include "floornav/sensing/obstacle_memory.hpp"

namespace floornav {

namespace {

// Below this a determinant is taken as zero (parallel lines), as RVO2 does.
constexpr double kParallel = 1e-9;
// s: the horizon of the still-point lines: at clearance c the robot may close in at c / 0.5 s,
// more than any preset's cruise speed at the follow-boundary distances, so they bind only when
// avoiding a robot would push the body at a wall.
constexpr double kStillHorizon = 0.5;
// m/s: how fast the heading may still close in on a still point at the margin (turn_first).
constexpr double kCreep = 1e-3;
// Keep right: rad/s at which a held robot turns its preferred velocity right, and how far.
constexpr double kBiasRate = 0.5;
constexpr double kMaxBias = kPi / 2.0;

// The line's permitted side does not hold v: v lies to the right of it.
bool violates(const OrcaLine& line, const Vec2& v) {
  return cross(line.direction, line.point - v) > 0.0;
}

// Program 1: the best velocity on line `i` within the speed disc and the lines before it;
// false when none is.
bool program_on_line(std::span<const OrcaLine> lines, std::size_t i, double radius, const Vec2& opt,
                     bool direction_opt, Vec2& result) {
  const OrcaLine& line = lines[i];
  const double dot = line.point.dot(line.direction);
  const double disc = dot * dot + radius * radius - line.point.squaredNorm();
  if (disc < 0.0) return false;  // the line misses the speed disc
  const double root = std::sqrt(disc);
  double t_left = -dot - root, t_right = -dot + root;
  for (std::size_t j = 0; j < i; ++j) {
    const double denominator = cross(line.direction, lines[j].direction);
    const double numerator = cross(lines[j].direction, line.point - lines[j].point);
    if (std::abs(denominator) <= kParallel) {
      if (numerator < 0.0) return false;  // parallel, and line i lies outside line j
      continue;
    }
    const double t = numerator / denominator;
    if (denominator >= 0.0)
      t_right = std::min(t_right, t);
    else
      t_left = std::max(t_left, t);
    if (t_left > t_right) return false;
  }
  if (direction_opt) {
    result = line.point + (opt.dot(line.direction) > 0.0 ? t_right : t_left) * line.direction;
  } else {
    const double t = std::clamp(line.direction.dot(opt - line.point), t_left, t_right);
    result = line.point + t * line.direction;
  }
  return true;
}

// Program 2: the velocity nearest to `opt` (or farthest along the direction `opt`) in the speed
// disc satisfying every line; returns the index of the first line it could not satisfy, or
// lines.size().
std::size_t program_2d(std::span<const OrcaLine> lines, double radius, const Vec2& opt,
                       bool direction_opt, Vec2& result) {
  if (direction_opt)
    result = opt * radius;
  else if (opt.squaredNorm() > radius * radius)
    result = opt.normalized() * radius;
  else
    result = opt;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (!violates(lines[i], result)) continue;
    const Vec2 before = result;
    if (!program_on_line(lines, i, radius, opt, direction_opt, result)) {
      result = before;
      return i;
    }
  }
  return lines.size();
}

// Program 3: no velocity satisfies every line; from line `begin` on, the velocity that
// minimises the largest violation of the soft lines, keeping the first `hard`.
void program_3d(std::span<const OrcaLine> lines, std::size_t hard, std::size_t begin, double radius,
                Vec2& result, std::vector<OrcaLine>& projected) {
  double distance = 0.0;
  for (std::size_t i = begin; i < lines.size(); ++i) {
    if (cross(lines[i].direction, lines[i].point - result) <= distance) continue;
    projected.assign(lines.begin(), lines.begin() + static_cast<std::ptrdiff_t>(hard));
    for (std::size_t j = hard; j < i; ++j) {
      OrcaLine line;
      const double det = cross(lines[i].direction, lines[j].direction);
      if (std::abs(det) <= kParallel) {
        if (lines[i].direction.dot(lines[j].direction) > 0.0) continue;  // same direction
        line.point = 0.5 * (lines[i].point + lines[j].point);
      } else {
        line.point =
            lines[i].point +
            (cross(lines[j].direction, lines[i].point - lines[j].point) / det) * lines[i].direction;
      }
      line.direction = normalized_or_zero(lines[j].direction - lines[i].direction);
      projected.push_back(line);
    }
    const Vec2 before = result;
    const Vec2 inward = rotate_ccw90(lines[i].direction);
    if (program_2d(projected, radius, inward, true, result) < projected.size()) result = before;
    distance = cross(lines[i].direction, lines[i].point - result);
  }
}

}  // namespace

OrcaLine orca_line(const Vec2& p, const Vec2& v_a, const Vec2& v_b, double r, double tau, double dt,
                   double responsibility) {
  const Vec2 v = v_a - v_b;
  const double dist_sq = p.squaredNorm();
  const double r_sq = r * r;
  OrcaLine line;
  Vec2 u;
  if (dist_sq > r_sq) {
    // w: from the centre of the cut-off disc (p / tau) to v.
    const Vec2 w = v - p / tau;
    const double w_sq = w.squaredNorm();
    const double dot1 = w.dot(p);
    if (dot1 < 0.0 && dot1 * dot1 > r_sq * w_sq) {
      // v is nearest to the cut-off disc: out along w.
      const double w_len = std::sqrt(w_sq);
      const Vec2 unit_w = w / w_len;
      line.direction = rotate_cw90(unit_w);
      u = (r / tau - w_len) * unit_w;
    } else {
      // v is nearest to a leg of the cone: the left leg when w is left of p.
      const double leg = std::sqrt(dist_sq - r_sq);
      if (cross(p, w) > 0.0)
        line.direction = Vec2(p.x() * leg - p.y() * r, p.x() * r + p.y() * leg) / dist_sq;
      else
        line.direction = -Vec2(p.x() * leg + p.y() * r, -p.x() * r + p.y() * leg) / dist_sq;
      u = v.dot(line.direction) * line.direction - v;
    }
  } else {
    // Overlapping: leave within one step.
    const Vec2 w = v - p / dt;
    const double w_len = w.norm();
    const Vec2 unit_w = w_len > 0.0 ? Vec2(w / w_len) : Vec2(-p.normalized());
    line.direction = rotate_cw90(unit_w);
    u = (r / dt - w_len) * unit_w;
  }
  line.point = v_a + responsibility * u;
  return line;
}

OrcaLine still_point_line(const Vec2& p, double r, double tau) {
  const double d = p.norm();
  const Vec2 n = d > 0.0 ? Vec2(p / d) : Vec2(1.0, 0.0);
  OrcaLine line;
  line.point = (std::max(d - r, 0.0) / tau) * n;
  line.direction = rotate_cw90(Vec2(-n));
  return line;
}

Vec2 solve_orca(std::span<const OrcaLine> lines, std::size_t hard, const Vec2& preferred,
                double max_speed, std::vector<OrcaLine>& projected) {
  Vec2 result = Vec2::Zero();
  const std::size_t failed = program_2d(lines, max_speed, preferred, false, result);
  if (failed < lines.size()) program_3d(lines, hard, failed, max_speed, result, projected);
  return result;
}

double robot_return_tolerance(const RobotSpec& robot) {
  return 1e-6 + 4.0 * robot.sensor_noise;
}

std::size_t drop_robot_points(std::span<const Vec2> points, std::span<const NearbyRobot> robots,
                              double tolerance, std::span<Vec2> out) {
  std::size_t n = 0;
  for (const Vec2& q : points) {
    bool robot = false;
    for (const NearbyRobot& b : robots) {
      const double reach = b.radius + tolerance;
      if (b.moving && (q - b.position).squaredNorm() <= reach * reach) {
        robot = true;
        break;
      }
    }
    if (!robot) out[n++] = q;
  }
  return n;
}

namespace {

// The robot does not drive u: it drives along its heading at |u| cos e (the pipeline of Fig 5.12,
// heading_tracker.hpp) while it turns towards u. Near a wall, that can close in on the wall
// although u does not; then u is scaled down until the speed along the heading satisfies the
// still lines too (the robot turns before it drives). A tiny u still turns the robot (a zero u
// would not: the pipeline holds still without a heading).
Vec2 turn_first(const Vec2& u, const Observation& obs, std::span<const OrcaLine> still) {
  const double speed = u.norm();
  if (speed <= 0.0 || still.empty()) return u;
  const NavigationParams& p = *obs.params;
  const Vec2 h(std::cos(obs.pose.theta), std::sin(obs.pose.theta));
  double v = std::min(speed, p.v0);
  if (p.slow_when_turning) v *= std::max(0.0, h.dot(u) / speed);
  const Vec2 drive = v * h;
  double scale = 1.0;
  for (const OrcaLine& line : still) {
    // The line's normal into the forbidden side, and its bound: drive . n <= bound.
    const Vec2 n = rotate_cw90(line.direction);
    // A creep of 1 mm/s is let through: a robot driving along a wall at its margin has the wall
    // at a right angle, and rounding would otherwise stop it dead.
    const double along = drive.dot(n), bound = std::max(line.point.dot(n), 0.0) + kCreep;
    if (along > bound) scale = std::min(scale, bound / along);
  }
  if (scale >= 1.0) return u;
  constexpr double kTurnOnly = 1e-6;  // m/s
  return u * std::max(scale, kTurnOnly / speed);
}

// A decision's working memory, one per thread rather than per robot (a fleet's robots decide one
// after another on each thread): 100,000 robots would otherwise carry ~14 KB each (PERFORMANCE.md,
// memory of 100,000 QuickBots). It grows, never shrinks: the thread that makes the layers has it
// sized for them (no allocation in its steps); a fleet's other worker threads size theirs at their
// first decision of each run_steps call.
struct OrcaWork {
  std::vector<Vec2> sensed;
  std::vector<std::uint32_t> nearest;  ///< the robots' indices ORCA avoids
  std::vector<double> distances;       ///< squared, of those robots
  std::vector<double> selected;        ///< the same, partly sorted
  OrcaScratch scratch;

  void fit(std::size_t n) {
    if (sensed.size() >= n) return;
    sensed.resize(n);
    nearest.reserve(256);
    distances.reserve(256);
    selected.reserve(256);
    scratch.lines.reserve(n + 64);
    scratch.projected.reserve(n + 64);
  }
};

OrcaWork& thread_orca_work() {
  thread_local OrcaWork work;
  return work;
}

class OrcaLayer final : public Controller {
 public:
  OrcaLayer(std::unique_ptr<Controller> inner, const RobotSpec& robot,
            const RobotAvoidanceParams& params, bool inner_reads_sensed)
      : Controller(inner->mode_names(), inner->guard_names()),
        inner_(std::move(inner)),
        params_(params),
        inner_reads_sensed_(inner_reads_sensed) {
    thread_orca_work().fit(robot.sensors.size() + ObstacleMemory::kCapacity);
  }

  Decision decide(const Observation& obs) override {
    if (std::none_of(obs.robots.begin(), obs.robots.end(),
                     [](const NearbyRobot& r) { return r.moving; }))
      return inner_->decide(obs);  // nobody to avoid: exactly the wrapped controller
    const NavigationParams& p = *obs.params;
    const double r_self = obs.robot->body_radius;
    OrcaWork& work = thread_orca_work();
    work.fit(obs.sensed.size());
    // The moving robots leave the observation: only the still world reaches the controller.
    // Remembered points hold none of them (RobotAgent::sense keeps moving robots' returns out of
    // the memory).
    Observation still = obs;
    const bool points_sensed = obs.points.data() == obs.sensed.data();
    if (inner_reads_sensed_ || points_sensed) {
      still.sensed = {work.sensed.data(),
                      drop_robot_points(obs.sensed, obs.robots, robot_return_tolerance(*obs.robot),
                                        work.sensed)};
      if (points_sensed) still.points = still.sensed;
    }
    const Decision d = inner_->decide(still);
    if (d.command.kind() != Command::Kind::Velocity) return d;

    // Hard lines: the still points near enough to bind at cruise speed; then one soft line per
    // moving robot.
    std::vector<OrcaLine>& lines = work.scratch.lines;
    lines.clear();
    const Vec2 x = obs.pose.position;
    // A sensed point lies a little beyond the wall's nearest point (beams are spread): the still
    // lines keep a margin of a quarter of the body radius (at most d_unsafe).
    const double r_still = r_self + std::min(p.d_unsafe, 0.25 * r_self);
    for (const Vec2& q : still.points) {
      const Vec2 rel = q - x;
      if (rel.norm() - r_still < p.v0 * kStillHorizon)
        lines.push_back(still_point_line(rel, r_still, kStillHorizon));
    }
    const std::size_t hard = lines.size();
    for (const std::uint32_t j : nearest_moving(obs.robots, x, 2.0 * p.v0 * obs.dt, work)) {
      const NearbyRobot& b = obs.robots[j];
      lines.push_back(orca_line(b.position - x, obs.velocity, b.velocity,
                                r_self + b.radius + params_.margin, params_.horizon, obs.dt, 0.5));
    }
    // Keep right, as at a roundabout: a robot that the others hold back turns its preferred
    // velocity to the right, the more the longer it is held (and back as it gets free), so that
    // robots that meet symmetrically (RVO2's Circle: all bound through one point) circle
    // counter-clockwise round the meeting and leave towards their goals, rather than stand.
    const Vec2 wanted = d.command.u();
    const Vec2 pref = rotate(wanted, -bias_);
    Vec2 u = solve_orca(lines, hard, pref, p.v0, work.scratch.projected);
    // Tries the way to its right (45 degrees) too, and takes it if that lets it move faster.
    if (u.norm() < 0.5 * pref.norm()) {
      static const double c = std::cos(-kPi / 4.0), s = std::sin(-kPi / 4.0);  // taken once
      const Vec2 right = solve_orca(lines, hard, rotate(pref, c, s), p.v0, work.scratch.projected);
      if (right.norm() > u.norm()) u = right;
    }
    const bool held = u.norm() < 0.5 * wanted.norm();
    bias_ = std::clamp(bias_ + (held ? 1.0 : -1.0) * kBiasRate * obs.dt, 0.0, kMaxBias);
    return {Command::velocity(turn_first(u, obs, {lines.data(), hard})), d.mode, d.guard};
  }

  void reset() override {
    inner_->reset();
    bias_ = 0.0;
    look_d2_ = kLookEverywhere;
  }
  int mode() const override { return inner_->mode(); }

 private:
  // The indices of the moving robots ORCA avoids: all of them, or the `neighbours` nearest to
  // `x` (by distance, then by index: the same order on every machine), in the order told.
  // Robots move little in a step: those nearer than the last step's k-th nearest plus `slack`
  // (two robots closing in at cruise speed) hold this step's k nearest whenever there are k of
  // them, and are few more than k. Otherwise every moving robot is looked at.
  std::span<const std::uint32_t> nearest_moving(std::span<const NearbyRobot> robots, const Vec2& x,
                                                double slack, OrcaWork& work) {
    const auto k = static_cast<std::size_t>(params_.neighbours);
    std::vector<std::uint32_t>& order = work.nearest;
    std::vector<double>& d2 = work.distances;
    if (order.size() < robots.size()) {
      order.resize(robots.size());
      d2.resize(robots.size());
    }
    std::size_t moving = 0;
    // The moving robots nearer than sqrt(limit), in the order told, without a branch.
    const auto within = [&](double limit) {
      std::size_t n = 0;
      moving = 0;
      for (std::size_t j = 0; j < robots.size(); ++j) {
        const double d = (robots[j].position - x).squaredNorm();
        order[n] = static_cast<std::uint32_t>(j);
        d2[n] = d;
        n += static_cast<std::size_t>(robots[j].moving & (d < limit));
        moving += static_cast<std::size_t>(robots[j].moving);
      }
      return n;
    };
    std::size_t n = within(look_d2_);
    if (n < k && n < moving) n = within(kLookEverywhere);
    if (n > k) n = keep_nearest(order.data(), d2.data(), n, k, work.selected);
    look_d2_ = kLookEverywhere;
    if (n == k) {
      const double kth = std::sqrt(*std::max_element(d2.begin(), d2.begin() + k));
      look_d2_ = (kth + slack) * (kth + slack);
    }
    return {order.data(), n};
  }

  // Keeps, in place and in order, the k of the n robots (indices, squared distances) that are
  // nearest by (distance, index); returns k.
  static std::size_t keep_nearest(std::uint32_t* index, double* d2, std::size_t n, std::size_t k,
                                  std::vector<double>& selected) {
    // The k nearest are those nearer than the k-th distance and, at that distance, the first.
    selected.assign(d2, d2 + n);
    const auto kth = selected.begin() + static_cast<std::ptrdiff_t>(k - 1);
    std::nth_element(selected.begin(), kth, selected.end());
    const double last = *kth;
    std::size_t at_last = k;
    for (std::size_t m = 0; m < n; ++m) at_last -= static_cast<std::size_t>(d2[m] < last);
    std::size_t kept = 0;
    for (std::size_t m = 0; m < n; ++m) {
      const bool tie = d2[m] == last && at_last > 0;
      at_last -= static_cast<std::size_t>(tie);
      index[kept] = index[m];
      d2[kept] = d2[m];
      kept += static_cast<std::size_t>(d2[m] < last || tie);
    }
    return kept;
  }

  static constexpr double kLookEverywhere = std::numeric_limits<double>::infinity();

  std::unique_ptr<Controller> inner_;
  RobotAvoidanceParams params_;
  bool inner_reads_sensed_;
  double bias_{0.0};  ///< rad: how far right the preferred velocity is turned (keep right)
  double look_d2_{kLookEverywhere};  ///< m^2: where nearest_moving looks first
};

}  // namespace

std::unique_ptr<Controller> make_orca_layer(std::unique_ptr<Controller> inner,
                                            const RobotSpec& robot,
                                            const RobotAvoidanceParams& params,
                                            bool inner_reads_sensed) {
  return std::make_unique<OrcaLayer>(std::move(inner), robot, params, inner_reads_sensed);
}

}  // namespace floornav
