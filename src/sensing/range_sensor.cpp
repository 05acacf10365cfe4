#include "floornav/sensing/range_sensor.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include <emmintrin.h>

#include "floornav/core/isa_clones.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/fan_cone.hpp"
#include "floornav/geometry/ray.hpp"
#include "floornav/sensing/sensor_fans.hpp"
#include "floornav/world/occupancy_grid.hpp"

namespace floornav {

namespace {

// Pose2::compose and Pose2::heading spelled out, with cos/sin of the robot's heading passed in:
// the same operations in the same order as rotate(), so the same bits.
Vec2 origin_of(const Pose2& robot, double c, double s, const RangeSensorSpec& spec) {
  // Component by component: a Vec2 of the rotated mount added as a vector is built in memory by
  // two scalar stores and read back as one packed load, a store-forwarding stall per beam (perf of
  // BM_Fleet_QuickBotWarehouse/1000/2 shows it). The same additions, so the same bits.
  const Vec2& m = spec.mount.position;
  return {robot.position.x() + (c * m.x() - s * m.y()),
          robot.position.y() + (s * m.x() + c * m.y())};
}

// Sums of a heading and a mount angle within this of 0 are at most one turn from (-pi, pi]: a
// robot's heading (within pi) plus a mount angle within a turn and a half.
constexpr double kOneTurnAway = 2.5 * kPi;

// `theta` wrapped into (-pi, pi] by at most one whole turn, for |theta| <= kOneTurnAway: a select
// rather than a loop (no branch in the beam loops). The turn is added exactly (Sterbenz: pi <=
// |theta| <= 4 pi): the result is theta's true wrap.
double wrap_turn(double theta) {
  const double up = theta <= -kPi ? theta + 2.0 * kPi : theta;
  return theta > kPi ? theta - 2.0 * kPi : up;
}

// The heading of a sensor mounted at `mount_theta` on a robot heading `robot_theta`: the exact
// sum, wrapped by a whole turn (per beam, where wrap_angle's atan2 would cost a sine, a cosine and
// an arctangent). A sum farther out (a mount angle far out of range) or not finite is left to
// wrap_angle.
double beam_heading(double robot_theta, double mount_theta) {
  const double theta = robot_theta + mount_theta;
  return std::abs(theta) <= kOneTurnAway ? wrap_turn(theta) : wrap_angle(theta);
}

// The beam of a single sensor: its direction is the mount's (cos, sin) turned by the robot's
// (c, s), the chapter's composition of the sensor frame with the robot frame, rather than a sine
// and a cosine of the summed heading per sensor per step. Inlined: a call costs as much as it does.
__attribute__((always_inline)) inline SensorBeam beam_of(const Pose2& robot, double c, double s,
                                                         const RangeSensorSpec& spec,
                                                         const Vec2& mount_dir) {
  SensorBeam b;
  b.origin = origin_of(robot, c, s, spec);
  b.theta = beam_heading(robot.theta, spec.mount.theta);
  const double mc = mount_dir.x(), ms = mount_dir.y();
  b.dir = Vec2(c * mc - s * ms, s * mc + c * ms);
  return b;
}

SensorBeam beam_of(const Pose2& robot, double c, double s, const RangeSensorSpec& spec) {
  return beam_of(robot, c, s, spec, mount_direction(spec));
}

// A margin against rounding: the disc's radius is a lower bound computed in floating point.
constexpr double kFreeMargin = 1e-9;  // m
// A ray that stays this far inside the free disc cannot meet a shape, even through the rounding of
// a ray-segment test (its collinear tolerance is 1e-12 m).
constexpr double kReachMargin = 1e-6;  // m

// The nearest of `others` along the ray, or `best` when none is nearer.
double nearest_disc(std::span<const Circle> others, const Vec2& origin, const Vec2& dir,
                    double best) {
  for (const Circle& c : others) best = ray_circle_hit(origin, dir, c, best);
  return best;
}

// The nearest of `boxes` along the ray, or `best` when none is nearer.
double nearest_box(std::span<const OrientedBox> boxes, const Vec2& origin, const Vec2& dir,
                   double best) {
  for (const OrientedBox& b : boxes)
    if (auto t = intersect_ray(b, origin, dir); t && *t < best) best = *t;
  return best;
}

// A sensor sees nothing beyond its range: noise is added only to real returns.
double finish_reading(double r, const RangeSensorSpec& s, double noise_stddev, Rng& rng) {
  if (noise_stddev > 0.0 && r < s.max_range) r += noise_stddev * rng.normal();
  return std::clamp(r, s.min_range, s.max_range);
}

__attribute__((always_inline)) inline double sense_one(const World& world, const SensorBeam& b,
                                                       const RangeSensorSpec& s,
                                                       double noise_stddev, Rng& rng,
                                                       const FreeDisc& free,
                                                       std::span<const Circle> others,
                                                       std::span<const OrientedBox> boxes) {
  const double free_radius = free.radius - kFreeMargin;
  const double from_centre2 = (b.origin - free.centre).squaredNorm();
  const bool known_free = free_radius > 0.0 && from_centre2 < free_radius * free_radius;
  // Every ray of the sensor ends inside the free disc: no shape of the world is within its reach,
  // so the world's cast would return max_range (or the occupancy grid's hit, which the disc does
  // not rule out), bit for bit, without walking its cells.
  const bool reach_free =
      known_free && std::sqrt(from_centre2) + s.max_range < free_radius - kReachMargin;
  const OccupancyGrid* grid = world.grid();
  const auto cast = [&](const Vec2& dir) {
    const double r = reach_free
                         ? (grid ? std::min(s.max_range, grid->cast_ray(b.origin, dir, s.max_range))
                                 : s.max_range)
                     : known_free ? world.cast_ray_from_free(b.origin, dir, s.max_range)
                                  : world.cast_ray(b.origin, dir, s.max_range);
    const double near = others.empty() ? r : nearest_disc(others, b.origin, dir, r);
    return boxes.empty() ? near : nearest_box(boxes, b.origin, dir, near);
  };
  double r = s.max_range;
  if (s.cone_rays <= 1 || s.cone_angle <= 0.0) {
    r = cast(b.dir);
  } else {
    for (int k = 0; k < s.cone_rays; ++k) {
      const double a = b.theta + s.cone_angle * (static_cast<double>(k) / (s.cone_rays - 1) - 0.5);
      r = std::min(r, cast(Vec2(std::cos(a), std::sin(a))));
    }
  }
  return finish_reading(r, s, noise_stddev, rng);
}

// Lidars: runs of at least this many single-beam sensors sharing an origin and a max_range are
// cast as one fan (World::cast_fan), in chunks of kFanChunk beams on the stack.
constexpr std::size_t kMinFanBeams = 16;
// A lidar's beam directions are turned from the previous beam's, and computed exactly every
// this many beams.
constexpr std::size_t kAnchorEvery = 32;
// Four doubles (GCC's vector extensions).
using V4d = double __attribute__((vector_size(32)));
constexpr std::size_t kFanChunk = 256;

bool single_beam(const RangeSensorSpec& s) {
  return s.cone_rays <= 1 || s.cone_angle <= 0.0;
}

// The end of the run of single-beam sensors from `i` with `i`'s origin and max_range, looked for
// from `from` (i, or a run end known to be on the way: a SensorLayout's).
std::size_t fan_end(std::span<const SensorBeam> beams, std::span<const RangeSensorSpec> sensors,
                    std::size_t i, std::size_t from) {
  std::size_t j = from;
  while (j < sensors.size() && single_beam(sensors[j]) && beams[j].origin == beams[i].origin &&
         sensors[j].max_range == sensors[i].max_range)
    ++j;
  return j;
}

// Sensors [i, end) of one run (see fan_end): the distances sense_one would cast, bit for bit,
// written to ranges[i, end). `spacing_known`: the run is (part of) a lidar's.
void cast_fan(const World& world, std::span<const SensorBeam> beams, std::size_t i, std::size_t end,
              double max_range, std::span<double> ranges, const FreeDisc& free, FanScratch& scratch,
              bool spacing_known) {
  const Vec2 origin = beams[i].origin;
  const double free_radius = free.radius - kFreeMargin;
  const bool known_free =
      free_radius > 0.0 && (origin - free.centre).squaredNorm() < free_radius * free_radius;
  std::array<Vec2, kFanChunk> dirs;
  std::array<double, kFanChunk> angles;
  for (std::size_t first = i; first < end; first += kFanChunk) {
    const std::size_t n = std::min(kFanChunk, end - first);
    for (std::size_t k = 0; k < n; ++k) {
      dirs[k] = beams[first + k].dir;
      angles[k] = beams[first + k].theta;
    }
    const std::span<double> out = ranges.subspan(first, n);
    if (known_free) {
      world.cast_fan_from_free(origin, {dirs.data(), n}, {angles.data(), n}, max_range, out,
                               scratch, spacing_known);
    } else {
      world.cast_fan(origin, {dirs.data(), n}, {angles.data(), n}, max_range, out, scratch,
                     spacing_known);
    }
  }
}

// The shape of the fan of beams [i, end) that fan_discs needs: whether it is even (within 1e-6
// rad of theta0 + k step, modulo 2 pi, and not overlapping itself after a full turn), its layout
// for FanCone, and, for a fan no wider than a half turn (a 180-degree lidar), its centre line:
// every beam is within pi / 2 + 1e-6 of it, so along the whole ray (p - o) . c >= -1e-6 t.
struct DiscFanShape {
  fan_detail::FanLayout layout;
  bool even;
  bool half_plane;
  Vec2 centre_dir;
};

DiscFanShape disc_fan_shape(std::span<const SensorBeam> beams, std::size_t i, std::size_t end) {
  const std::size_t n = end - i;
  const double theta0 = beams[i].theta;
  const double step = n > 1 ? wrap_angle(beams[i + 1].theta - theta0) : 0.0;
  bool even = step > 0.0 && fan_detail::evenly_spaced(
                                theta0, step, n, [&](std::size_t k) { return beams[i + k].theta; },
                                std::nextafter(1e-6, 0.0));
  // Beams that overlap after a full turn are all tested (as are uneven ones).
  even = even && static_cast<double>(n - 1) * step <= 2.0 * kPi - 0.5 * step;
  DiscFanShape shape;
  shape.layout.first = theta0;
  shape.layout.step = step;
  shape.layout.inv_step = even ? 1.0 / step : 0.0;
  shape.layout.n = static_cast<int>(n);
  shape.even = even;
  const double half_width = 0.5 * static_cast<double>(n - 1) * step;
  shape.half_plane = even && half_width <= 0.5 * kPi + 1e-9;
  const double centre_angle = theta0 + half_width;
  shape.centre_dir =
      shape.half_plane ? Vec2(std::cos(centre_angle), std::sin(centre_angle)) : Vec2::Zero();
  return shape;
}

// Every beam of `beams` (n of them) against disc `c`, lowering ranges[k] to each hit.
void disc_every_beam(const SensorBeam* beams, std::size_t n, const Vec2& origin, const Circle& c,
                     double* ranges) {
  for (std::size_t k = 0; k < n; ++k)
    ranges[k] = ray_circle_hit(origin, beams[k].dir, c, ranges[k]);
}

// Beam k against the disc as disc_span tests it, alone.
[[gnu::always_inline]] inline void disc_beam(const SensorBeam* beams, std::size_t k, double mx,
                                             double my, double cc, double near, double* ranges) {
  double& range = ranges[k];
  if (!(range > near)) return;
  const Vec2& dir = beams[k].dir;
  const double b = mx * dir.x() + my * dir.y();
  if (b > 0.0) return;
  const double disc = b * b - cc;
  if (disc < 0.0) return;
  const double t = -b - std::sqrt(disc);
  if (t < range) range = t;
}

// The beams k0 to k1 against the disc whose intersect_ray numbers that do not depend on the beam
// are m = origin - centre and cc = |m|^2 - r^2 (once for all, the same bits; the origin is
// outside the disc, so a beam hits at -b - sqrt(b^2 - cc) unless it points away, b > 0, or
// passes by, b^2 < cc), only where its range so far is beyond `near`. Two beams at a time:
// SSE2's lanes do the scalar test's IEEE operations in its order (b, b * b - cc, -b - the root),
// and a lane takes t where it would (range > near, b not > 0, t < range; a negative b * b - cc
// has a NaN root, which no comparison takes), so the ranges are the same to the bit.
[[gnu::always_inline]] inline void disc_span(const SensorBeam* beams, int k0, int k1, double mx,
                                             double my, double cc, double near, double* ranges) {
  const __m128d vmx = _mm_set1_pd(mx), vmy = _mm_set1_pd(my), vcc = _mm_set1_pd(cc);
  const __m128d vnear = _mm_set1_pd(near), sign = _mm_set1_pd(-0.0), zero = _mm_setzero_pd();
  std::size_t k = static_cast<std::size_t>(k0);
  const auto last = static_cast<std::size_t>(k1);
  for (; k < last; k += 2) {
    const __m128d d0 = _mm_loadu_pd(beams[k].dir.data());
    const __m128d d1 = _mm_loadu_pd(beams[k + 1].dir.data());
    const __m128d b = _mm_add_pd(_mm_mul_pd(vmx, _mm_unpacklo_pd(d0, d1)),
                                 _mm_mul_pd(vmy, _mm_unpackhi_pd(d0, d1)));
    const __m128d root = _mm_sqrt_pd(_mm_sub_pd(_mm_mul_pd(b, b), vcc));
    const __m128d t = _mm_sub_pd(_mm_xor_pd(b, sign), root);
    double* range = ranges + k;
    const __m128d r = _mm_loadu_pd(range);
    const __m128d take = _mm_andnot_pd(_mm_cmpgt_pd(b, zero),
                                       _mm_and_pd(_mm_cmpgt_pd(r, vnear), _mm_cmplt_pd(t, r)));
    _mm_storeu_pd(range, _mm_or_pd(_mm_and_pd(take, t), _mm_andnot_pd(take, r)));
  }
  if (k == last) disc_beam(beams, k, mx, my, cc, near, ranges);
}

// Other robots' bodies on a fan of beams [i, end) that share an origin, lowering ranges[k] to
// each hit; every range is at most max_range on entry. For evenly spaced beams each disc is
// tested only against the beams within its angular extent widened by 1e-5 rad on each side and
// by FanCone's margin (1e-4 rad) (a beam's angle is within 1e-6 rad of its place in the fan, the
// cone's table gives the bearing's bin exactly and its bounds to within 3e-7 rad, the half-width
// is an upper bound of asin(r / d), a grazing ray-disc test's rounding orders of magnitude below
// the rest), and only where the beam's range so far is beyond the
// disc's distance d - r (less 1e-6 (1 + d), far more than the rounding of a ray-disc hit, which
// is never nearer than d - r), so the result is the all-pairs loop's, bit for bit: the same
// test, and the minimum does not depend on the order. Otherwise, every pair.
void fan_discs(std::span<const SensorBeam> beams, std::size_t i, std::size_t end, double max_range,
               std::span<const Circle> others, std::span<double> ranges) {
  const std::size_t n = end - i;
  const Vec2 origin = beams[i].origin;
  const SensorBeam* fan_beams = beams.data() + i;
  double* fan_ranges = ranges.data() + i;
  const DiscFanShape shape = disc_fan_shape(beams, i, end);
  if (!shape.even) {  // an uneven fan: every pair
    for (const Circle& c : others) disc_every_beam(fan_beams, n, origin, c, fan_ranges);
    return;
  }
  const fan_detail::FanCone cone(shape.layout, 0.0);
  for (const Circle& c : others) {
    const Vec2 v = c.center - origin;
    // Behind the lidar first: half the bodies a fleet hands in are (it gathers them within the
    // sensors' reach, so the test of `far` rarely skips one). A disc more than its radius behind
    // the origin along the centre line of a half-turn fan (with a margin far above the rounding
    // of the ray-disc test, at any distance within reach) meets no beam.
    const double far = max_range + c.radius + 1.0;
    if (shape.half_plane && v.dot(shape.centre_dir) < -(c.radius + 1e-5 * (1.0 + far))) continue;
    // Beyond max_range + r + 1 m, the test against `near` below would skip the disc: no root.
    if (v.squaredNorm() > far * far) continue;
    const double d = v.norm();
    if (d <= c.radius + 1e-9) {  // the origin inside the body
      disc_every_beam(fan_beams, n, origin, c, fan_ranges);
      continue;
    }
    // No beam reaches the disc before its range ends.
    const double near = d - c.radius - 1e-6 * (1.0 + d);
    if (near >= max_range) continue;
    const Vec2 m = origin - c.center;
    const double cc = m.squaredNorm() - c.radius * c.radius;
    if (!(cc > 0.0)) {
      disc_every_beam(fan_beams, n, origin, c, fan_ranges);
      continue;
    }
    // The half-width: asin(r / d) <= tan(asin(r / d)) = r / sqrt(d^2 - r^2), with cc for
    // d^2 - r^2 (rounded to a relative 4e-16 d^2 / cc: with d > r + 1e-9, below 2e-7 r / 1 m,
    // as 1 - (r / d)^2 was, far below the 1e-5 added). From cc, not d: its root and division
    // wait on no other root or division (the latency of the disc's chain halves).
    const double half = std::min(kPi, c.radius / std::sqrt(cc)) + 1e-5;
    cone.for_spans_about(v.x(), v.y(), half, [&](int k0, int k1) {
      disc_span(fan_beams, k0, k1, m.x(), m.y(), cc, near, fan_ranges);
    });
  }
}

// Moving rectangles on a fan of beams [i, end) that share an origin, lowering ranges[k] to each
// hit; a box wholly beyond the fan's range is skipped.
void fan_boxes(std::span<const SensorBeam> beams, std::size_t i, std::size_t end, double max_range,
               std::span<const OrientedBox> boxes, std::span<double> ranges) {
  const Vec2 origin = beams[i].origin;
  for (const OrientedBox& box : boxes) {
    const double reach = max_range + box.bounding_radius();
    if ((box.center - origin).squaredNorm() > reach * reach) continue;
    for (std::size_t k = i; k < end; ++k)
      if (auto t = intersect_ray(box, origin, beams[k].dir); t && *t < ranges[k]) ranges[k] = *t;
  }
}

// A lidar in the sensor list: the end of the run from `i` of single-beam sensors on one mount
// point whose headings are evenly spaced (to 1e-9 rad), or i + 1.
std::size_t lidar_end(std::span<const RangeSensorSpec> sensors, std::size_t i) {
  if (i + 1 >= sensors.size() || !single_beam(sensors[i])) return i + 1;
  const double spacing = sensors[i + 1].mount.theta - sensors[i].mount.theta;
  if (!(std::abs(spacing) > 0.0 && std::abs(spacing) < kPi)) return i + 1;
  std::size_t j = i + 1;
  while (j < sensors.size() && single_beam(sensors[j]) &&
         sensors[j].mount.position == sensors[i].mount.position &&
         std::abs(sensors[j].mount.theta - sensors[i].mount.theta -
                  static_cast<double>(j - i) * spacing) < 1e-9)
    ++j;
  return j;
}

// The turn between neighbouring beams of the lidar [i, end) (see lidar_end): by the mean
// spacing, since two neighbours' difference would carry their rounding into every turn.
Vec2 lidar_turn(std::span<const RangeSensorSpec> sensors, std::size_t i, std::size_t end) {
  const double spacing =
      (sensors[end - 1].mount.theta - sensors[i].mount.theta) / static_cast<double>(end - 1 - i);
  return {std::cos(spacing), std::sin(spacing)};
}

// The beams of the lidar [i, end): its first beam's origin for all, the exact sum of headings
// wrapped by whole turns (not wrap_angle's atan2: this is per beam), and each direction turned
// from the previous one by `turn` (a rotation, not a sine and a cosine per beam), re-anchored
// exactly every kAnchorEvery beams, so directions stay within ~1e-15 of the exact ones.
// `mount_theta(k)` is sensors[k].mount.theta (from a contiguous copy where there is one).
template <class MountTheta>
void lidar_beams(const Pose2& robot, double c, double s, std::span<const RangeSensorSpec> sensors,
                 std::size_t i, std::size_t end, const Vec2& turn, std::span<SensorBeam> beams,
                 const MountTheta& mount_theta) {
  // Copies, not references: the stores to `beams` must not make the compiler reload them.
  const Vec2 origin = origin_of(robot, c, s, sensors[i]);
  const double ox = origin.x(), oy = origin.y();
  const double robot_theta = robot.theta, tx = turn.x(), ty = turn.y();
  const auto put = [&](std::size_t k, double x, double y, double theta) {
    SensorBeam& b = beams[k];
    b.origin.x() = ox;
    b.origin.y() = oy;
    b.dir.x() = x;
    b.dir.y() = y;
    b.theta = theta;
  };
  // The mount angles of a lidar lie between its first's and its last's: when this holds, every
  // sum is within kOneTurnAway, and wrap_turn wraps it (beam_heading's guard once, not per beam;
  // the same bits either way).
  const bool within_turns =
      std::abs(robot_theta) +
          std::max(std::abs(sensors[i].mount.theta), std::abs(sensors[end - 1].mount.theta)) <=
      kOneTurnAway;
  const auto by_turns = [&](std::size_t k) { return wrap_turn(robot_theta + mount_theta(k)); };
  const auto guarded = [&](std::size_t k) { return beam_heading(robot_theta, mount_theta(k)); };
  // The chains of kAnchorEvery beams from each anchor are independent: stepped side by side
  // (four at a time, the last ones too), each rotation's latency overlaps the others' (one chain
  // after another waits on every multiply). Each chain does the same operations as alone: the
  // same bits.
  // Up to four chains of kAnchorEvery beams from `first`, the last one ending at `stop`, side by
  // side as the lanes of one vector (GCC's vector extensions; SSE2 pairs outside the x86-64-v3
  // clone): one operation per rotation for all, lane by lane the same. Unused lanes stay 0.
  const auto chains = [&](std::size_t first, std::size_t stop, const auto& heading) {
    const std::size_t count = (stop - first + kAnchorEvery - 1) / kAnchorEvery;
    V4d xs{}, ys{};
    for (std::size_t a = 0; a < count; ++a) {
      const std::size_t anchor = first + a * kAnchorEvery;
      const double theta0 = heading(anchor);
      xs[a] = std::cos(theta0);
      ys[a] = std::sin(theta0);
      put(anchor, xs[a], ys[a], theta0);
    }
    const auto rotate = [&] {
      const V4d px = xs, py = ys;
      xs = px * tx - py * ty;
      ys = px * ty + py * tx;
    };
    if (stop - first == 4 * kAnchorEvery) {  // four whole chains: no lane to leave out
      for (std::size_t j = 1; j < kAnchorEvery; ++j) {
        rotate();
        for (std::size_t a = 0; a < 4; ++a) {
          const std::size_t k = first + a * kAnchorEvery + j;
          put(k, xs[a], ys[a], heading(k));
        }
      }
      return;
    }
    const std::size_t longest = std::min(kAnchorEvery, stop - first);
    for (std::size_t j = 1; j < longest; ++j) {
      rotate();
      for (std::size_t a = 0; a < count; ++a) {
        const std::size_t k = first + a * kAnchorEvery + j;
        if (k < stop) put(k, xs[a], ys[a], heading(k));
      }
    }
  };
  const auto all = [&](const auto& heading) {
    for (std::size_t k = i; k < end; k += 4 * kAnchorEvery)
      chains(k, std::min(end, k + 4 * kAnchorEvery), heading);
  };
  if (within_turns)
    all(by_turns);
  else
    all(guarded);
}

// sense_ranges over runs: `run_end(i)` is fan_end(beams, sensors, i, i); `layout` (may be null)
// gives the ranges contiguous for the noiseless clamp.
template <class RunEnd>
void sense_runs(const World& world, std::span<const SensorBeam> beams,
                std::span<const RangeSensorSpec> sensors, const SensorLayout* layout,
                double noise_stddev, Rng& rng, std::span<double> ranges, FanScratch& scratch,
                const FreeDisc& free, std::span<const Circle> others,
                std::span<const OrientedBox> boxes, const RunEnd& run_end) {
  // Fewer sensors than a fan needs: each is cast on its own, as below.
  if (sensors.size() < kMinFanBeams) {
    for (std::size_t i = 0; i < sensors.size(); ++i)
      ranges[i] = sense_one(world, beams[i], sensors[i], noise_stddev, rng, free, others, boxes);
    return;
  }
  for (std::size_t i = 0; i < sensors.size();) {
    const std::size_t end = run_end(i);
    if (end - i >= kMinFanBeams) {
      // Cast first (the world, then other robots' bodies), then draw the noise sensor by
      // sensor: the RNG sees the same order.
      cast_fan(world, beams, i, end, sensors[i].max_range, ranges, free, scratch,
               layout != nullptr && end == layout->fan_end(i) && layout->even_run(i));
      if (!others.empty()) fan_discs(beams, i, end, sensors[i].max_range, others, ranges);
      if (!boxes.empty()) fan_boxes(beams, i, end, sensors[i].max_range, boxes, ranges);
      if (layout && !(noise_stddev > 0.0)) {
        // finish_reading without noise: the clamp alone, over contiguous bounds.
        const std::span<const double> lo = layout->min_ranges(), hi = layout->max_ranges();
        for (; i < end; ++i) ranges[i] = std::clamp(ranges[i], lo[i], hi[i]);
      } else {
        for (; i < end; ++i) ranges[i] = finish_reading(ranges[i], sensors[i], noise_stddev, rng);
      }
    } else {
      const std::size_t stop = std::max(end, i + 1);  // at least one (a cone sensor)
      for (; i < stop; ++i)
        ranges[i] = sense_one(world, beams[i], sensors[i], noise_stddev, rng, free, others, boxes);
    }
  }
}

}  // namespace

Vec2 mount_direction(const RangeSensorSpec& sensor) {
  return {std::cos(sensor.mount.theta), std::sin(sensor.mount.theta)};
}

SensorLayout::SensorLayout(std::span<const RangeSensorSpec> sensors)
    : fan_end_(sensors.size()),
      max_range_(sensors.size()),
      min_range_(sensors.size()),
      mount_theta_(sensors.size()),
      mount_dir_(sensors.size()) {
  const std::size_t n = sensors.size();
  for (std::size_t i = 0; i < n; ++i) {
    min_range_[i] = sensors[i].min_range;
    mount_theta_[i] = sensors[i].mount.theta;
    max_range_[i] = sensors[i].max_range;
    mount_dir_[i] = mount_direction(sensors[i]);
  }
  // compute_sensor_beams' walk (none with fewer sensors than a lidar).
  for (std::size_t i = 0; n >= kMinFanBeams && i < n;) {
    const std::size_t end = lidar_end(sensors, i);
    if (end - i < kMinFanBeams) {
      ++i;
      continue;
    }
    lidars_.push_back({i, end, lidar_turn(sensors, i, end)});
    i = end;
  }
  // fan_end from the back: when i + 1 is on i's run, i's run ends where i + 1's does (== is
  // transitive among the numbers that compare equal to themselves).
  const auto same = [&](std::size_t j, std::size_t i) {
    return single_beam(sensors[j]) && sensors[j].mount.position == sensors[i].mount.position &&
           sensors[j].max_range == sensors[i].max_range;
  };
  for (std::size_t i = n; i-- > 0;) {
    if (!same(i, i))
      fan_end_[i] = i;
    else if (i + 1 < n && same(i + 1, i))
      fan_end_[i] = fan_end_[i + 1];
    else
      fan_end_[i] = i + 1;
  }
  // The runs as sense_runs walks them, each checked for even spacing once here.
  even_run_.assign(n, 0);
  std::vector<double> thetas;
  for (std::size_t i = 0; i < n;) {
    const std::size_t end = std::max(fan_end_[i], i + 1);
    thetas.clear();
    for (std::size_t k = i; k < end; ++k) thetas.push_back(sensors[k].mount.theta);
    // even_fan lays the run out (and checks its step); the spacing is checked here alone, to
    // the tighter tolerance.
    if (const auto fan = fan_detail::even_fan(thetas, /*spacing_known=*/true))
      even_run_[i] = fan_detail::evenly_spaced(
          fan->first, fan->step, thetas.size(), [&](std::size_t k) { return thetas[k]; },
          0.5 * fan_detail::kFanAngleTol);
    i = end;
  }
}

void compute_sensor_beams(const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                          std::span<SensorBeam> beams) {
  const double c = std::cos(robot.theta), s = std::sin(robot.theta);
  // Fewer sensors than a lidar's run (IR rings, sonars): no run to look for.
  if (sensors.size() < kMinFanBeams) {
    for (std::size_t i = 0; i < sensors.size(); ++i) beams[i] = beam_of(robot, c, s, sensors[i]);
    return;
  }
  for (std::size_t i = 0; i < sensors.size();) {
    const std::size_t end = lidar_end(sensors, i);
    if (end - i < kMinFanBeams) {
      beams[i] = beam_of(robot, c, s, sensors[i]);
      ++i;
      continue;
    }
    lidar_beams(robot, c, s, sensors, i, end, lidar_turn(sensors, i, end), beams,
                [&](std::size_t k) { return sensors[k].mount.theta; });
    i = end;
  }
}

void compute_sensor_beams(const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                          const SensorLayout& layout, std::span<SensorBeam> beams) {
  compute_sensor_beams(robot, Vec2(std::cos(robot.theta), std::sin(robot.theta)), sensors, layout,
                       beams);
}

FLOORNAV_ISA_CLONES
void compute_sensor_beams(const Pose2& robot, const Vec2& heading,
                          std::span<const RangeSensorSpec> sensors, const SensorLayout& layout,
                          std::span<SensorBeam> beams) {
  const double c = heading.x(), s = heading.y();
  std::size_t i = 0;
  for (const SensorLayout::Lidar& lidar : layout.lidars()) {
    for (; i < lidar.begin; ++i) beams[i] = beam_of(robot, c, s, sensors[i], layout.mount_dir(i));
    const double* mount_theta = layout.mount_thetas().data();
    lidar_beams(robot, c, s, sensors, lidar.begin, lidar.end, lidar.turn, beams,
                [mount_theta](std::size_t k) { return mount_theta[k]; });
    i = lidar.end;
  }
  for (; i < sensors.size(); ++i) beams[i] = beam_of(robot, c, s, sensors[i], layout.mount_dir(i));
}

void sense_ranges(const World& world, std::span<const SensorBeam> beams,
                  std::span<const RangeSensorSpec> sensors, double noise_stddev, Rng& rng,
                  std::span<double> ranges, FanScratch& scratch, const FreeDisc& free,
                  std::span<const Circle> others, std::span<const OrientedBox> boxes) {
  sense_runs(world, beams, sensors, nullptr, noise_stddev, rng, ranges, scratch, free, others,
             boxes, [&](std::size_t i) { return fan_end(beams, sensors, i, i); });
}

FLOORNAV_ISA_CLONES
void sense_ranges(const World& world, std::span<const SensorBeam> beams,
                  std::span<const RangeSensorSpec> sensors, const SensorLayout& layout,
                  double noise_stddev, Rng& rng, std::span<double> ranges, FanScratch& scratch,
                  const FreeDisc& free, std::span<const Circle> others,
                  std::span<const OrientedBox> boxes) {
  const auto run_end = [&](std::size_t i) {
    const Vec2& origin = beams[i].origin;
    if (!(origin == origin)) return fan_end(beams, sensors, i, i);  // NaN: no run
    // The sensors on i's mount point share its origin (the same arithmetic on the same
    // numbers); others may meet it by rounding: the run goes on as fan_end's would.
    return fan_end(beams, sensors, i, layout.fan_end(i));
  };
  sense_runs(world, beams, sensors, &layout, noise_stddev, rng, ranges, scratch, free, others,
             boxes, run_end);
}

void sense_ranges(const World& world, std::span<const SensorBeam> beams,
                  std::span<const RangeSensorSpec> sensors, double noise_stddev, Rng& rng,
                  std::span<double> ranges, const FreeDisc& free, std::span<const Circle> others,
                  std::span<const OrientedBox> boxes) {
  FanScratch scratch;
  sense_ranges(world, beams, sensors, noise_stddev, rng, ranges, scratch, free, others, boxes);
}

FLOORNAV_ISA_CLONES
std::size_t ranges_to_points(std::span<const SensorBeam> beams, std::span<const double> max_ranges,
                             std::span<const double> ranges, std::span<Vec2> points) {
  // Every point is written and kept when its beam saw something: no branch on the readings
  // (hits and misses alternate along a scan). points[n] is within the span (n <= i).
  std::size_t n = 0;
  for (std::size_t i = 0; i < max_ranges.size(); ++i) {
    points[n] = beams[i].origin + ranges[i] * beams[i].dir;
    n += !(ranges[i] >= max_ranges[i]);
  }
  return n;
}

void sense_ranges(const World& world, const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                  double noise_stddev, Rng& rng, std::span<double> ranges) {
  const double c = std::cos(robot.theta), s = std::sin(robot.theta);
  for (std::size_t i = 0; i < sensors.size(); ++i)
    ranges[i] = sense_one(world, beam_of(robot, c, s, sensors[i]), sensors[i], noise_stddev, rng,
                          FreeDisc{}, {}, {});
}

std::size_t ranges_to_points(const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                             std::span<const double> ranges, std::span<Vec2> points) {
  const double c = std::cos(robot.theta), s = std::sin(robot.theta);
  std::size_t n = 0;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (ranges[i] >= sensors[i].max_range) continue;
    const SensorBeam b = beam_of(robot, c, s, sensors[i]);
    points[n++] = b.origin + ranges[i] * b.dir;
  }
  return n;
}

}  // namespace floornav
