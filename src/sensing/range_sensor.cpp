#include "floornav/sensing/range_sensor.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/ray.hpp"
#include "floornav/world/occupancy_grid.hpp"

namespace floornav {

namespace {

// Pose2::compose and Pose2::heading spelled out, with cos/sin of the robot's heading passed in:
// the same operations in the same order as rotate(), so the same bits.
SensorBeam beam_of(const Pose2& robot, double c, double s, const RangeSensorSpec& spec) {
  const Vec2& m = spec.mount.position;
  SensorBeam b;
  b.origin = robot.position + Vec2(c * m.x() - s * m.y(), s * m.x() + c * m.y());
  b.theta = wrap_angle(robot.theta + spec.mount.theta);
  b.dir = Vec2(std::cos(b.theta), std::sin(b.theta));
  return b;
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

double sense_one(const World& world, const SensorBeam& b, const RangeSensorSpec& s,
                 double noise_stddev, Rng& rng, const FreeDisc& free,
                 std::span<const Circle> others, std::span<const OrientedBox> boxes) {
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
constexpr std::size_t kFanChunk = 256;

bool single_beam(const RangeSensorSpec& s) {
  return s.cone_rays <= 1 || s.cone_angle <= 0.0;
}

// The end of the run of single-beam sensors from `i` with `i`'s origin and max_range.
std::size_t fan_end(std::span<const SensorBeam> beams, std::span<const RangeSensorSpec> sensors,
                    std::size_t i) {
  std::size_t j = i;
  while (j < sensors.size() && single_beam(sensors[j]) && beams[j].origin == beams[i].origin &&
         sensors[j].max_range == sensors[i].max_range)
    ++j;
  return j;
}

// Sensors [i, end) of one run (see fan_end): the distances sense_one would cast, bit for bit,
// written to ranges[i, end).
void cast_fan(const World& world, std::span<const SensorBeam> beams, std::size_t i, std::size_t end,
              double max_range, std::span<double> ranges, const FreeDisc& free,
              FanScratch& scratch) {
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
                               scratch);
    } else {
      world.cast_fan(origin, {dirs.data(), n}, {angles.data(), n}, max_range, out, scratch);
    }
  }
}

// An angle reduced into (-pi, pi] by whole turns: within ~1e-15 rad of wrap_angle (which takes an
// atan2, a sine and a cosine for an angle out of range), for the tolerance tests below.
double reduce_turns(double a) {
  return a > -kPi && a <= kPi ? a : a - 2.0 * kPi * std::nearbyint(a / (2.0 * kPi));
}

// Other robots' bodies on a fan of beams [i, end) that share an origin, lowering ranges[k] to
// each hit; every range is at most max_range on entry. For evenly spaced beams each disc is
// tested only against the beams within its angular extent widened by 1e-5 rad on each side (a
// beam's angle is within 1e-6 rad of its place in the fan, the extent's bearing within 2e-6 rad
// of atan2's, its half-width an upper bound of asin(r / d), a grazing ray-disc test's rounding
// orders of magnitude below the rest),
// and only where the beam's range so far is beyond the disc's distance d - r (less 1e-6
// (1 + d), far more than the rounding of a ray-disc hit, which is never nearer than d - r), so
// the result is the all-pairs loop's, bit for bit: the same test, and the minimum does not
// depend on the order. Otherwise, every pair.
void fan_discs(std::span<const SensorBeam> beams, std::size_t i, std::size_t end, double max_range,
               std::span<const Circle> others, std::span<double> ranges) {
  const std::size_t n = end - i;
  const Vec2 origin = beams[i].origin;
  const double theta0 = beams[i].theta;
  const double step = n > 1 ? wrap_angle(beams[i + 1].theta - theta0) : 0.0;
  bool even = step > 0.0;
  for (std::size_t k = 0; even && k < n; ++k)
    even =
        std::abs(reduce_turns(beams[i + k].theta - theta0 - static_cast<double>(k) * step)) < 1e-6;
  const bool full_circle = even && static_cast<double>(n) * step > 2.0 * kPi - 0.5 * step;
  const double inv_step = even ? 1.0 / step : 0.0;
  // A fan no wider than a half turn (a 180-degree lidar): every beam is within pi / 2 + 1e-6 of
  // its centre line c, so along the whole ray (p - o) . c >= -1e-6 t, and a disc more than its
  // radius behind the origin along c (with a margin far above that and the rounding of the
  // ray-disc test, at any distance within reach) meets no beam: skipped without an atan2.
  const double half_width = 0.5 * static_cast<double>(n - 1) * step;
  const bool half_plane = even && half_width <= 0.5 * kPi + 1e-9;
  const double centre_angle = theta0 + half_width;
  const Vec2 centre_dir =
      half_plane ? Vec2(std::cos(centre_angle), std::sin(centre_angle)) : Vec2::Zero();
  const auto test = [&](std::size_t k, const Circle& c) {
    ranges[i + k] = ray_circle_hit(origin, beams[i + k].dir, c, ranges[i + k]);
  };
  for (const Circle& c : others) {
    const Vec2 v = c.center - origin;
    // Beyond max_range + r + 1 m, the test against `near` below would skip the disc: no root.
    const double far = max_range + c.radius + 1.0;
    if (even && v.squaredNorm() > far * far) continue;
    if (half_plane && v.dot(centre_dir) < -(c.radius + 1e-5 * (1.0 + far))) continue;
    const double d = v.norm();
    if (!even || d <= c.radius + 1e-9) {  // uneven fan, or the origin inside the body
      for (std::size_t k = 0; k < n; ++k) test(k, c);
      continue;
    }
    // No beam reaches the disc before its range ends.
    const double near = d - c.radius - 1e-6 * (1.0 + d);
    if (near >= max_range) continue;
    const auto test_near = [&](std::size_t k) {
      if (ranges[i + k] > near) test(k, c);
    };
    // asin(x) <= x / sqrt(1 - x^2) (= tan(asin x)); x < 1 here.
    const double x = c.radius / d;
    const double half = std::min(kPi, x / std::sqrt(1.0 - x * x)) + 1e-5;
    double rel = reduce_turns(coarse_atan2(v.y(), v.x()) - theta0);
    if (rel < 0.0) rel += 2.0 * kPi;  // [0, 2 pi)
    // The extent as beam offsets from beam 0; for a fan that does not go all the way round, an
    // extent that crosses 0 or 2 pi also shows a turn earlier or later (beam 0 is at offset 0
    // and every beam below 2 pi: a turn later only matters when the extent reaches below 0, a
    // turn earlier when it reaches 2 pi).
    const auto count = static_cast<long>(n);
    const auto beams_about = [&](double centre) {
      // Beams ceil(from) to floor(to), by truncation (std::ceil and std::floor are a dozen
      // instructions each without SSE4.1); the product by 1 / step is within ulps of the
      // quotient, far inside the margin.
      const double from = (centre - half) * inv_step, to = (centre + half) * inv_step;
      auto lo = static_cast<long>(from), hi = static_cast<long>(to);
      if (static_cast<double>(lo) < from) ++lo;
      if (static_cast<double>(hi) > to) --hi;
      if (full_circle) {
        for (long k = lo; k <= hi && k < lo + count; ++k)
          test_near(static_cast<std::size_t>(((k % count) + count) % count));
      } else {
        for (long k = std::max(lo, 0L); k <= std::min(hi, count - 1); ++k)
          test_near(static_cast<std::size_t>(k));
      }
    };
    beams_about(rel);
    if (!full_circle) {  // the modulo above covers both sides of a full circle
      if (rel + half >= 2.0 * kPi) beams_about(rel - 2.0 * kPi);
      if (rel - half <= 0.0) beams_about(rel + 2.0 * kPi);
    }
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

}  // namespace

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
    // A lidar: its first beam as above, then each next one turned by the fixed spacing (a
    // rotation, not a sine and a cosine per beam; re-anchored exactly every kAnchorEvery beams,
    // so directions stay within ~1e-15 of the exact ones).
    // The mean spacing: two neighbours' difference would carry their rounding into every turn.
    const double spacing =
        (sensors[end - 1].mount.theta - sensors[i].mount.theta) / static_cast<double>(end - 1 - i);
    const Vec2 turn(std::cos(spacing), std::sin(spacing));
    const SensorBeam first = beam_of(robot, c, s, sensors[i]);
    for (std::size_t k = i; k < end; ++k) {
      SensorBeam& b = beams[k];
      b.origin = first.origin;
      // The exact sum, wrapped by whole turns (not wrap_angle's atan2: this is per beam).
      double theta = robot.theta + sensors[k].mount.theta;
      while (theta > kPi) theta -= 2.0 * kPi;
      while (theta <= -kPi) theta += 2.0 * kPi;
      b.theta = theta;
      if ((k - i) % kAnchorEvery == 0) {
        b.dir = Vec2(std::cos(theta), std::sin(theta));
      } else {
        const Vec2& prev = beams[k - 1].dir;
        b.dir = Vec2(prev.x() * turn.x() - prev.y() * turn.y(),
                     prev.x() * turn.y() + prev.y() * turn.x());
      }
    }
    i = end;
  }
}

void sense_ranges(const World& world, std::span<const SensorBeam> beams,
                  std::span<const RangeSensorSpec> sensors, double noise_stddev, Rng& rng,
                  std::span<double> ranges, FanScratch& scratch, const FreeDisc& free,
                  std::span<const Circle> others, std::span<const OrientedBox> boxes) {
  // Fewer sensors than a fan needs: each is cast on its own, as below.
  if (sensors.size() < kMinFanBeams) {
    for (std::size_t i = 0; i < sensors.size(); ++i)
      ranges[i] = sense_one(world, beams[i], sensors[i], noise_stddev, rng, free, others, boxes);
    return;
  }
  for (std::size_t i = 0; i < sensors.size();) {
    const std::size_t end = fan_end(beams, sensors, i);
    if (end - i >= kMinFanBeams) {
      // Cast first (the world, then other robots' bodies), then draw the noise sensor by
      // sensor: the RNG sees the same order.
      cast_fan(world, beams, i, end, sensors[i].max_range, ranges, free, scratch);
      if (!others.empty()) fan_discs(beams, i, end, sensors[i].max_range, others, ranges);
      if (!boxes.empty()) fan_boxes(beams, i, end, sensors[i].max_range, boxes, ranges);
      for (; i < end; ++i) ranges[i] = finish_reading(ranges[i], sensors[i], noise_stddev, rng);
    } else {
      const std::size_t stop = std::max(end, i + 1);  // at least one (a cone sensor)
      for (; i < stop; ++i)
        ranges[i] = sense_one(world, beams[i], sensors[i], noise_stddev, rng, free, others, boxes);
    }
  }
}

void sense_ranges(const World& world, std::span<const SensorBeam> beams,
                  std::span<const RangeSensorSpec> sensors, double noise_stddev, Rng& rng,
                  std::span<double> ranges, const FreeDisc& free, std::span<const Circle> others,
                  std::span<const OrientedBox> boxes) {
  FanScratch scratch;
  sense_ranges(world, beams, sensors, noise_stddev, rng, ranges, scratch, free, others, boxes);
}

std::size_t ranges_to_points(std::span<const SensorBeam> beams,
                             std::span<const RangeSensorSpec> sensors,
                             std::span<const double> ranges, std::span<Vec2> points) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    if (ranges[i] >= sensors[i].max_range) continue;
    points[n++] = beams[i].origin + ranges[i] * beams[i].dir;
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
