#include "floornav/nav/safety_layer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

#include "floornav/geometry/polygon.hpp"
#include "floornav/geometry/segment.hpp"
#include "floornav/robot/body_clearance.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// m between two sampled poses of the stopping path, at most (fewer samples on long paths: the
// slack between samples is then up to half their spacing).
constexpr double kSampleSpacing = 0.005;
constexpr int kMaxSamples = 32;
// m: rounding allowed in a slack (a robot exactly at its margin may move straight away).
constexpr double kTolerance = 1e-9;
// Bisection steps of the largest allowed speed: 1/256 of the wanted speed.
constexpr int kBisections = 8;

}  // namespace

// What the measures of one filter call share: they all start from one pose.
struct SafetyShared {
  // Range returns kept by index below; with more near ones, every measure goes over them all.
  static constexpr std::size_t kMaxNear = 256;
  ClearanceHint hint;  // every clearance is measured near the pose
  // The body's clearance to the world at the pose, measured on first use.
  bool has_clearance{false};
  double clearance{0.0};
  // The range returns that a stopping path sweeping at most `reach_bound` may come near (in the
  // scene's order, with their squared distances from the pose): the others are beyond every
  // such path, and count only through the nearest of them (`far_d2`).
  bool has_near{false};
  double reach_bound{0.0};
  std::size_t near_count{0};
  std::array<std::uint32_t, kMaxNear> near_index;
  std::array<double, kMaxNear> near_d2;
  double far_d2{kInf};
  // The pose's heading (cos, sin), where the first stopping path is sampled.
  bool has_heading{false};
  Vec2 heading;
};

// The point that set a measure's least slack. When the world set it, its nearest point is a
// search (five clearances): left to the caller, which needs it only when the command is limited.
struct SafetyBlocker {
  Vec2 point{Vec2::Zero()};
  bool world{false};
};

namespace {

// The poses along a stopping path, from the pose (k = 0) to the path's end (k = count - 1).
// The arrays are left uninitialised (only the first `count` are written and read): a measure
// makes one, and most paths have a few samples of the 33. `time`, `centre_spacing` and
// `centre_sagitta` are filled only for bodies that move (time_samples).
struct PathSamples {
  std::array<Vec2, kMaxSamples + 1> position;
  std::array<double, kMaxSamples + 1> theta;
  std::array<Vec2, kMaxSamples + 1> axis;  ///< (cos, sin) of each pose's heading
  /// s from now at which the robot passes each pose (+infinity on a path that does not move the
  /// centre: it stands, turning at most)
  std::array<double, kMaxSamples + 1> time;
  int count{1};
  double spacing{0.0};         ///< m: the most any body point moves between two samples
  double centre_spacing{0.0};  ///< m: the most the centre moves between two samples
  /// m: how far the centre's arc strays from the chord between two samples
  double centre_sagitta{0.0};
  /// m: how far the centre's arc strays from the chord between the first and the last sample
  /// (+infinity: it turns by more than half a turn, and may come back beyond the chord's ends)
  double stray{0.0};
};

// When the centre has come `s` m along a stopping path driven at `speed` for `drive` s and then
// braked at `decel`: the time, s.
double time_along(double s, double speed, double drive, double decel) {
  if (!(speed > 0.0)) return kInf;
  const double cruise = speed * drive;
  if (s <= cruise) return s / speed;
  const double rest = std::max(0.0, speed * speed - 2.0 * decel * (s - cruise));
  return drive + (speed - std::sqrt(rest)) / decel;
}

// Fills `s` (fresh) with the samples' poses (their times: time_samples).
// `heading` is pose.heading().
void sample_path(const Pose2& pose, const Vec2& heading, const UnicycleCommand& path, double reach,
                 PathSamples& s) {
  s.position[0] = pose.position;
  s.theta[0] = pose.theta;
  s.axis[0] = heading;
  const int segments =
      reach > 0.0 ? std::clamp(static_cast<int>(std::ceil(reach / kSampleSpacing)), 1, kMaxSamples)
                  : 0;
  // Along the arc of length path.v turning by path.omega (the unicycle's exact solution): the
  // heading turns by the same angle from sample to sample, one sine and cosine for the path.
  const double turn = segments > 0 ? path.omega / segments : 0.0;
  const Vec2 step(std::cos(turn), std::sin(turn));
  const bool straight = std::abs(path.omega) < 1e-9;
  const double bend = straight ? 0.0 : path.v / path.omega;
  const Vec2 a0 = s.axis[0];
  for (int k = 1; k <= segments; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    const Vec2 a = s.axis[i - 1];
    s.axis[i] = Vec2(a.x() * step.x() - a.y() * step.y(), a.x() * step.y() + a.y() * step.x());
    const double f = static_cast<double>(k) / segments;
    const Vec2 moved = straight
                           ? Vec2(f * path.v * a0)
                           : Vec2(bend * (s.axis[i].y() - a0.y()), bend * (a0.x() - s.axis[i].x()));
    s.position[i] = pose.position + moved;
    s.theta[i] = pose.theta + f * path.omega;
  }
  s.count = segments + 1;
  if (segments > 0) s.spacing = reach / segments;
  if (!straight)
    s.stray = std::abs(path.omega) <= std::numbers::pi
                  ? std::abs(bend) * (1.0 - std::cos(0.5 * path.omega))
                  : kInf;
}

// Fills what projections along the centre's path need of `s` sampled along `path`: the times,
// driven as in time_along, and the centre's spacing and sagitta.
void time_samples(const UnicycleCommand& path, double speed, double drive, double decel,
                  PathSamples& s) {
  s.time[0] = 0.0;
  const int segments = s.count - 1;
  for (int k = 1; k <= segments; ++k) {
    const double f = static_cast<double>(k) / segments;
    s.time[static_cast<std::size_t>(k)] = time_along(f * std::abs(path.v), speed, drive, decel);
  }
  if (segments > 0) {
    s.centre_spacing = std::abs(path.v) / segments;
    const double t = std::abs(path.omega / segments);
    if (t > 0.0) s.centre_sagitta = s.centre_spacing / t * (1.0 - std::cos(0.5 * t));
  }
}

// The least a 1-Lipschitz function of the path (a distance, a projection) can be between two
// samples that read a and b, `spacing` apart along the path.
double between(double a, double b, double spacing) {
  return 0.5 * (a + b - spacing);
}

// Signed distance from a point (world frame) to the footprint at `position` (heading (cos, sin)
// = `axis`): negative inside.
double footprint_gap(std::span<const Vec2> footprint, const Vec2& position, const Vec2& axis,
                     const Vec2& q) {
  const Vec2 d0 = q - position;
  const Vec2 local(axis.x() * d0.x() + axis.y() * d0.y(), -axis.y() * d0.x() + axis.x() * d0.y());
  const double d = boundary_distance(footprint, local);
  return contains(footprint, local) ? -d : d;
}

// The unit vector from the box's nearest boundary point to `p` (p outside the box), or from the
// centre when p is inside.
Vec2 away_from_box(const OrientedBox& b, const Vec2& p) {
  const Vec2 local = b.to_local(p);
  const Vec2 nearest(std::clamp(local.x(), -b.half.x(), b.half.x()),
                     std::clamp(local.y(), -b.half.y(), b.half.y()));
  Vec2 d = local - nearest;
  if (d.squaredNorm() == 0.0) d = local;
  const Vec2 across(-b.axis.y(), b.axis.x());
  const Vec2 world = d.x() * b.axis + d.y() * across;
  const double n = world.norm();
  return n > 0.0 ? Vec2(world / n) : Vec2(1.0, 0.0);
}

// The nearest point of the world's obstacles to `p`: down the clearance's gradient (central
// differences; its direction is exact away from the medial axis).
Vec2 nearest_world_point(const World& world, const Vec2& p, ClearanceHint& hint) {
  constexpr double h = 1e-4;  // m
  const Vec2 dx(h, 0.0), dy(0.0, h);
  const Vec2 g(world.clearance(p + dx, hint) - world.clearance(p - dx, hint),
               world.clearance(p + dy, hint) - world.clearance(p - dy, hint));
  const double n = g.norm();
  if (!(n > 0.0)) return p;
  return p - world.clearance(p, hint) * (g / n);
}

// The least slack of a half-plane constraint along the sampled centre path: the projection of
// the centre's displacement on `n` must stay >= `need` plus, for a body that comes on its own,
// `approach` x (the time passed, up to one step `dt`). Between two samples the projection runs
// along the chord (strayed from by the arc's sagitta at most) at a constant speed while the robot
// cruises, and so does the need: their difference is least at one of the two samples.
double projection_slack(const PathSamples& s, const Vec2& n, double need, double approach,
                        double dt) {
  auto need_at = [&](double t) { return need + approach * std::min(1.0, t / dt); };
  if (s.count == 1) return -need_at(kInf);
  double worst = kInf;
  double before = -need;  // the slack at the pose itself, now
  for (int k = 1; k < s.count; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    const double now = n.dot(s.position[i] - s.position[0]) - need_at(s.time[i]);
    worst = std::min(worst, std::min(before, now) - s.centre_sagitta);
    before = now;
  }
  return worst;
}

// The stopping path's samples, taken on first use: most measures clear every obstacle by a
// bound and never need them.
class LazySamples {
 public:
  LazySamples(const Pose2& pose, const UnicycleCommand& path, double reach, double speed,
              double drive, double decel, SafetyShared& shared)
      : pose_(pose),
        path_(path),
        reach_(reach),
        speed_(speed),
        drive_(drive),
        decel_(decel),
        shared_(shared) {}

  const PathSamples& operator()() {
    if (!sampled_) {
      if (!shared_.has_heading) shared_.heading = pose_.heading();
      shared_.has_heading = true;
      sample_path(pose_, shared_.heading, path_, reach_, samples_);
    }
    sampled_ = true;
    return samples_;
  }

  // With the times at which the robot passes each sample: only bodies that move need them.
  const PathSamples& timed() {
    operator()();
    if (!timed_) time_samples(path_, speed_, drive_, decel_, samples_);
    timed_ = true;
    return samples_;
  }

 private:
  const Pose2& pose_;
  const UnicycleCommand& path_;
  double reach_, speed_, drive_, decel_;
  SafetyShared& shared_;
  PathSamples samples_;
  bool sampled_{false};
  bool timed_{false};
};

// The least slack found so far and, when asked for, the point that set it.
struct LeastSlack {
  double worst{kInf};
  SafetyBlocker* blocker{nullptr};

  void take(double slack, const Vec2& at) {
    if (blocker && slack < worst) *blocker = {at, false};
    worst = std::min(worst, slack);
  }
};

// What one measure() compares against everything: the body, where it is, how far its stopping
// path sweeps, and the margin to keep.
struct MeasuredBody {
  const RobotSpec& robot;
  const Pose2& pose;
  double reach;   ///< m: the farthest any body point moves along the stopping path
  double margin;  ///< m
  double bound;   ///< m: the radius of the disc round the body (its own disc, or the footprint's)
  double travel;  ///< m: the length of the centre's stopping path
  double dt;      ///< s
  LazySamples& samples;
  /// Only whether the slack is >= stop matters: below it, measuring may stop (-inf: exact).
  double stop;
  /// A slack at or above this may be reported as any value at or above it (+inf: exact).
  double exact_below;
};

// The body's clearance to the world at the filter's pose, measured once per filter call.
double pose_clearance(const World& world, const RobotSpec& robot, const Pose2& pose,
                      SafetyShared& shared) {
  if (!shared.has_clearance) shared.clearance = body_clearance(world, robot, pose, shared.hint);
  shared.has_clearance = true;
  return shared.clearance;
}

// The least of a gap's interval bounds along the sampled path minus `need`, the gaps measured by
// `gap(k)` and `before` the gap at the pose itself. Stops early once below `stop`.
template <typename Gap>
double path_slack(const PathSamples& s, Gap gap, double need, double before, double stop = -kInf) {
  double least = s.count == 1 ? before - need : kInf;
  for (int k = 1; k < s.count && !(least < stop); ++k) {
    const double now = gap(static_cast<std::size_t>(k));
    least = std::min(least, between(before, now, s.spacing) - need);
    before = now;
  }
  return least;
}

// The world: by the lower bound when it clears the whole sweep, else measured along the path.
void world_slack(const MeasuredBody& body, const World& world, double world_clearance,
                 SafetyShared& shared, LeastSlack& least) {
  const double bound = world_clearance - body.reach - body.margin;
  if (bound >= 0.0) {
    least.worst = std::min(least.worst, bound);
    return;
  }
  const double before = pose_clearance(world, body.robot, body.pose, shared);
  if (body.robot.footprint.empty()) {
    // A disc body's centre is k spacings along the path at sample k, so the clearance there is
    // at least before - k spacing (it is 1-Lipschitz) and path_slack's bound between samples k - 1
    // and k at least that too: none is below before - reach - margin, which, when it settles the
    // question, stands for them all without measuring one.
    const double settled = before - body.reach - body.margin;
    if (settled >= body.exact_below) {
      least.worst = std::min(least.worst, settled);
      return;
    }
  }
  const PathSamples& s = body.samples();
  const double need = std::min(body.margin, before);
  ClearanceHint& hint = shared.hint;
  const double slack = path_slack(
      s,
      [&](std::size_t k) {
        return body_clearance(world, body.robot, Pose2{s.position[k], s.theta[k]}, hint);
      },
      need, before, body.stop);
  // The world is marked as what blocked; filter finds its nearest point when it needs it.
  if (least.blocker && s.count > 1 && slack < least.worst) least.blocker->world = true;
  least.worst = std::min(least.worst, slack);
}

// The squared distance beyond which a range return is clear of every stopping path that sweeps
// at most `reach`.
double clear_d2(const MeasuredBody& body, double reach) {
  const double clear = (body.bound + reach + body.margin) * (1.0 + 1e-9);
  return clear * clear;
}

// One range return `q`, `d2` squared metres from the pose, like a piece of the world. Points
// clearly beyond the sweep are compared by squared distance (`nearest_clear`), the nearest one's
// root taken once (the same value: the root is monotonic and correctly rounded).
void point_slack(const MeasuredBody& body, const Vec2& q, double d2, double& nearest_clear,
                 LeastSlack& least) {
  const double reach = body.reach, margin = body.margin;
  if (d2 >= clear_d2(body, reach)) {
    nearest_clear = std::min(nearest_clear, d2);
    return;
  }
  const double lower = std::sqrt(d2) - body.bound;  // a lower bound on the gap now
  if (lower - reach - margin >= 0.0) {
    least.worst = std::min(least.worst, lower - reach - margin);
    return;
  }
  const PathSamples& s = body.samples();
  // No sample's gap is below the gap to the chord of the centre's path less how far the path
  // strays from it, and path_slack's bounds between samples no more than half a spacing below
  // theirs: when that settles the question, no sample is measured.
  const double settled = distance(Segment{s.position[0], s.position[s.count - 1]}, q) - s.stray -
                         body.bound - 0.5 * s.spacing - margin;
  if (settled >= body.exact_below) {
    least.worst = std::min(least.worst, settled);
    return;
  }
  // The disc round the body first: its gaps are lower bounds, and the need is at most the
  // margin, so a pass here is a pass (for a disc body it is the exact test).
  const bool disc = body.robot.footprint.empty();
  auto disc_gap = [&](std::size_t k) { return (q - s.position[k]).norm() - body.bound; };
  const double disc_before = disc_gap(0);
  double point_worst = path_slack(s, disc_gap, disc ? std::min(margin, disc_before) : margin,
                                  disc_before, body.stop);
  if (!disc && point_worst < 0.0) {
    auto gap = [&](std::size_t k) {
      return footprint_gap(body.robot.footprint, s.position[k], s.axis[k], q);
    };
    const double before = gap(0);
    point_worst = path_slack(s, gap, std::min(margin, before), before, body.stop);
  }
  least.take(point_worst, q);
}

// Sorts the range returns, once per filter call, into those a stopping path sweeping at most
// `body.reach` may come near and the rest. False when there are too many near ones to keep.
bool sort_points(const MeasuredBody& body, const SafetyScene& scene, SafetyShared& shared) {
  shared.has_near = true;
  shared.reach_bound = body.reach;
  const Vec2 p = body.pose.position;
  const double clear2 = clear_d2(body, body.reach);
  if (scene.points_origin == p && scene.points_nearest_d2 >= clear2) {  // all far: no pass
    shared.far_d2 = scene.points_nearest_d2;
    return true;
  }
  const std::span<const Vec2> points = scene.points;
  double far = kInf;
  std::size_t near = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d2 = (points[i] - p).squaredNorm();
    if (d2 >= clear2) {
      far = std::min(far, d2);
      continue;
    }
    if (near == SafetyShared::kMaxNear) {
      shared.reach_bound = -kInf;  // no measure uses the list
      return false;
    }
    shared.near_index[near] = static_cast<std::uint32_t>(i);
    shared.near_d2[near++] = d2;
  }
  shared.far_d2 = far;
  shared.near_count = near;
  return true;
}

// This step's range returns, each like a piece of the world. A path that sweeps no farther than
// the filter's first goes over the near ones only, in the scene's order (the least slack and the
// point that set it are those of the whole set: the others are all clear of the sweep, and count
// by the nearest of them).
void points_slack(const MeasuredBody& body, const SafetyScene& scene, SafetyShared& shared,
                  LeastSlack& least) {
  const std::span<const Vec2> points = scene.points;
  if (!shared.has_near) sort_points(body, scene, shared);
  double nearest_clear = kInf;
  if (body.reach <= shared.reach_bound) {
    nearest_clear = shared.far_d2;
    for (std::size_t j = 0; j < shared.near_count && !(least.worst < body.stop); ++j) {
      const std::uint32_t i = shared.near_index[j];
      point_slack(body, points[i], shared.near_d2[j], nearest_clear, least);
    }
  } else {
    const Vec2 p = body.pose.position;
    for (std::size_t i = 0; i < points.size() && !(least.worst < body.stop); ++i)
      point_slack(body, points[i], (points[i] - p).squaredNorm(), nearest_clear, least);
  }
  if (nearest_clear < kInf)
    least.worst =
        std::min(least.worst, std::sqrt(nearest_clear) - body.bound - body.reach - body.margin);
}

// Bodies that move: half-planes across the line between the centres. The robot's own body
// counts as its disc here, as the simulator measures contacts between bodies.
void movers_slack(const MeasuredBody& body, const SafetyScene& scene, LeastSlack& least) {
  const Vec2 p = body.pose.position;
  const double radius = body.robot.body_radius;
  for (const SafetyDisc& b : scene.discs) {
    const Vec2 d = p - b.position;
    const double distance = d.norm();
    const double room = distance - radius - b.radius - body.margin - b.extra_margin;
    // Reciprocal: half the room beyond the margin (none once inside it). Otherwise the room
    // less what the other body may close in one step (which may ask the robot to back off).
    const double need = b.reciprocal ? 0.5 * std::min(0.0, -room) : std::min(0.0, -room);
    const double approach = b.reciprocal ? 0.0 : b.approach;
    if (-body.travel - need - approach >= 0.0) {
      least.worst = std::min(least.worst, -body.travel - need - approach);
      continue;
    }
    const Vec2 n = distance > 0.0 ? Vec2(d / distance) : Vec2(body.pose.heading());
    least.take(projection_slack(body.samples.timed(), n, need, approach, body.dt),
               b.position + b.radius * n);
  }
  for (const SafetyBox& b : scene.boxes) {
    const double gap = signed_distance(b.box, p) - radius;
    const double need = std::min(0.0, body.margin - gap);
    if (-body.travel - need - b.approach >= 0.0) {
      least.worst = std::min(least.worst, -body.travel - need - b.approach);
      continue;
    }
    const Vec2 n = away_from_box(b.box, p);
    least.take(projection_slack(body.samples.timed(), n, need, b.approach, body.dt),
               p - (gap + radius) * n);
  }
}

}  // namespace

SafetyLayer::SafetyLayer(const RobotSpec& robot, const SafetyParams& params, double dt)
    : robot_(&robot), params_(params), dt_(dt) {
  for (const Vec2& q : robot.footprint) body_reach_ = std::max(body_reach_, q.norm());
}

double SafetyLayer::gap_reach() const {
  const double top = max_forward_speed(robot_->drive);
  return params_.margin + params_.person_margin + params_.slowdown_distance +
         2.0 * std::abs(stopping_path({top, 0.0}).v);
}

UnicycleCommand SafetyLayer::stopping_path(const UnicycleCommand& c) const {
  const double drive = dt_ + params_.reaction_time;
  const double v = std::abs(c.v), w = std::abs(c.omega);
  const double length = v * drive + v * v / (2.0 * robot_->max_acceleration);
  // Braking keeps to the command's arc (V and omega slow together, as a base following an arc
  // brakes): the turn is the arc's curvature times its length. A turn on the spot stops with the
  // step: the simulator's bases stop at once, and a field is sized by the travel speed (ISO
  // 3691-4); braking a fast spin at the presets' modest angular limits would sweep a footprint
  // round a whole turn.
  const double turn = w * drive + w * v / (2.0 * robot_->max_acceleration);
  return {std::copysign(length, c.v), std::copysign(turn, c.omega)};
}

double SafetyLayer::sweep_reach(const UnicycleCommand& path) const {
  return std::abs(path.v) + std::abs(path.omega) * body_reach_;
}

double SafetyLayer::slack(const Pose2& pose, const UnicycleCommand& command,
                          const SafetyScene& scene) const {
  SafetyShared shared;
  return measure(pose, command, scene, nullptr, shared, -kInf, kInf);
}

double SafetyLayer::measure(const Pose2& pose, const UnicycleCommand& command,
                            const SafetyScene& scene, SafetyBlocker* blocker, SafetyShared& shared,
                            double decide, double exact_below) const {
  const UnicycleCommand path = stopping_path(command);
  const double reach = sweep_reach(path);
  LazySamples samples(pose, path, reach, std::abs(command.v), dt_ + params_.reaction_time,
                      robot_->max_acceleration, shared);
  const double bound = robot_->footprint.empty() ? robot_->body_radius : body_reach_;
  const MeasuredBody body{.robot = *robot_,
                          .pose = pose,
                          .reach = reach,
                          .margin = params_.margin,
                          .bound = bound,
                          .travel = std::abs(path.v),
                          .dt = dt_,
                          .samples = samples,
                          .stop = decide,
                          .exact_below = exact_below};
  LeastSlack least{kInf, blocker};
  if (scene.world) world_slack(body, *scene.world, scene.world_clearance, shared, least);
  if (!(least.worst < decide)) points_slack(body, scene, shared, least);
  if (!(least.worst < decide)) movers_slack(body, scene, least);
  return least.worst;
}

double SafetyLayer::slowdown_cap(const Pose2& pose, const SafetyScene& scene,
                                 SafetyShared& shared) const {
  const double field = params_.slowdown_distance;
  if (field <= 0.0) return kInf;
  const Vec2 p = pose.position;
  const double radius = robot_->footprint.empty() ? robot_->body_radius : body_reach_;
  bool inside = false;
  if (scene.world && scene.world_clearance < field)
    inside = pose_clearance(*scene.world, *robot_, pose, shared) < field;
  for (const Vec2& q : scene.points) inside = inside || (q - p).norm() - radius < field;
  for (const SafetyDisc& b : scene.discs)
    inside = inside || (b.position - p).norm() - robot_->body_radius - b.radius < field;
  for (const SafetyBox& b : scene.boxes)
    inside = inside || signed_distance(b.box, p) - robot_->body_radius < field;
  return inside ? params_.slowdown_speed : kInf;
}

UnicycleCommand SafetyLayer::way_out(const Pose2& pose, const SafetyScene& scene,
                                     SafetyShared& shared) const {
  const DiffDriveParams& drive = robot_->drive;
  const double v = 0.25 * max_forward_speed(drive), w = 0.5 * max_turn_rate(drive);
  const std::array<UnicycleCommand, 9> options{{
      {0.0, 0.0},
      {-v, 0.0},
      {v, 0.0},
      {-v, w},
      {-v, -w},
      {v, w},
      {v, -w},
      {0.0, w},
      {0.0, -w},
  }};
  UnicycleCommand best{};
  double best_slack = -kInf;
  for (const UnicycleCommand& o : options) {
    const UnicycleCommand c = wheels_to_unicycle(drive, saturate_wheels(drive, o));
    const double s = measure(pose, c, scene, nullptr, shared, -kInf, kInf);
    if (s > best_slack + kTolerance) {
      best_slack = s;
      best = c;
    }
  }
  return best;
}

SafetyVerdict SafetyLayer::filter(const Pose2& pose, const UnicycleCommand& wanted,
                                  const SafetyScene& scene) const {
  UnicycleCommand c = wanted;
  SafetyShared shared;  // every measure below starts from this pose
  const double cap = slowdown_cap(pose, scene, shared);
  if (std::abs(c.v) > cap) c.v = std::copysign(cap, c.v);
  // What standing still keeps: normally a slack >= 0; below 0 when a body that moves on its own
  // is coming in and the robot can no longer keep its field by standing. Then any command that
  // keeps no less than standing does is allowed (the controller's own way out among them).
  // A command that keeps its field passes whatever standing keeps (the floor is at most
  // -kTolerance): the common case costs one measure. The slacks of the wanted command, of
  // standing and of the commands tried are compared with thresholds at or below 0 only: above 0
  // they need not be exact.
  SafetyBlocker blocker{pose.position};
  auto slack_of = [&](const UnicycleCommand& u, double exact_below) {
    return measure(pose, u, scene, nullptr, shared, -kInf, exact_below);
  };
  const double wanted_slack = measure(pose, c, scene, &blocker, shared, -kInf, 0.0);
  if (wanted_slack >= -kTolerance) return {c, c.v != wanted.v || c.omega != wanted.omega};
  const double floor = std::min(0.0, slack_of(UnicycleCommand{}, 0.0)) - kTolerance;
  auto allowed = [&](const UnicycleCommand& u) {
    return measure(pose, u, scene, nullptr, shared, floor, 0.0) >= floor;
  };
  if (wanted_slack >= floor) return {c, c.v != wanted.v || c.omega != wanted.omega};
  SafetyVerdict verdict;
  verdict.limited = true;
  if (blocker.world) blocker.point = nearest_world_point(*scene.world, pose.position, shared.hint);
  verdict.blocker = blocker.point;
  verdict.blocked = blocker.point != pose.position;

  // The largest fraction s of `c` (scaled by `scale`) that is allowed, knowing that s = 0 is.
  auto largest = [&](auto scale) {
    double lo = 0.0, hi = 1.0;
    for (int i = 0; i < kBisections; ++i) {
      const double mid = 0.5 * (lo + hi);
      (allowed(scale(mid)) ? lo : hi) = mid;
    }
    return scale(lo);
  };
  // Keep the turn (a disc body turns on the spot without moving), shed the speed; a footprint
  // that cannot turn here either slows both.
  const UnicycleCommand turn{0.0, c.omega};
  if (allowed(turn))
    verdict.command = largest([&](double s) { return UnicycleCommand{s * c.v, c.omega}; });
  else
    verdict.command = largest([&](double s) { return UnicycleCommand{s * c.v, s * c.omega}; });
  // Something is coming in: a way out that keeps more than the controller's command does.
  if (floor < -kTolerance) {
    const UnicycleCommand out = way_out(pose, scene, shared);
    if (slack_of(out, kInf) > slack_of(verdict.command, kInf) + kTolerance) verdict.command = out;
  }
  return verdict;
}

}  // namespace floornav
