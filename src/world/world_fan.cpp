#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "floornav/core/isa_clones.hpp"
#include "floornav/geometry/fan_cone.hpp"
#include "floornav/geometry/fan_layout.hpp"
#include "floornav/geometry/ray.hpp"
#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

// World::cast_fan: a lidar's beams from one origin, each obstacle near enough gathered once and
// tested against the beams its angular extent covers.

namespace floornav {

namespace {

using fan_detail::even_fan;
using fan_detail::FanLayout;

// Which obstacles the current fan has taken: item i when marks[i] == epoch; and the segments it
// gathered (their index entries). One set per thread, not per caller: a thread that senses many
// robots in turn (VecEnv's copies) finds them in the cache, where each robot's own were cold by
// its next step.
struct FanMarks {
  std::vector<std::uint32_t> marks;
  std::uint32_t epoch{0};
  std::vector<std::uint32_t> entries;
};

// The thread's marks ready for a fan over `items` obstacles, of which `segments` segments; sets
// `epoch` and `entries` (room for every segment, and one more). Allocates only when the world has
// more obstacles than the thread has seen.
std::uint32_t* fresh_marks(std::size_t items, std::size_t segments, std::uint32_t& epoch,
                           std::uint32_t*& entries) {
  thread_local FanMarks m;
  if (m.marks.size() < items) m.marks.resize(items, 0);
  // One past the segments: the gathering writes an entry before it knows whether to keep it.
  if (m.entries.size() <= segments) m.entries.resize(segments + 1);
  if (++m.epoch == 0) {
    std::fill(m.marks.begin(), m.marks.end(), 0);
    m.epoch = 1;
  }
  epoch = m.epoch;
  entries = m.entries.data();
  return m.marks.data();
}

// `out` (the grid's casts) as cast_ray_from_free has them: min(max_range, the grid's cast_ray).
// Every cast of the grid is max_range or std::min(a finite time, max_range), so for a positive
// max_range (+inf included) the minimum changes no bit and is left out; otherwise (0, -0, a
// negative range or NaN) the sign of a zero or a NaN may change, and it is taken.
void at_most(double max_range, std::span<double> out) {
  if (max_range > 0.0) return;
  for (double& r : out) r = std::min(max_range, r);
}

// Whether a range is zero (either sign): a scan without a branch per beam, where they are rare.
bool any_zero(std::span<const double> out) {
  std::size_t i = 0;
  bool zero = false;
#if defined(__SSE2__)
  const __m128d z = _mm_setzero_pd();
  __m128d found = z;
  for (; i + 1 < out.size(); i += 2)
    found = _mm_or_pd(found, _mm_cmpeq_pd(_mm_loadu_pd(&out[i]), z));
  zero = _mm_movemask_pd(found) != 0;
#endif
  for (; i < out.size(); ++i) zero |= out[i] == 0.0;
  return zero;
}

// Beams k0 to k1 against segment [a, b] (edge e = b - a), each hit kept when nearer than
// out[k]: ray_segment_hit, two beams at a time where SSE2 is. The lanes do its IEEE operations
// in its order (cross(w, e) is the same for every beam) and take t where it would (t >= 0,
// t < out[k], u within the segment's slack: a NaN u passes, as there), so the ranges are the same
// to the bit; a pair with a beam parallel to the segment is left to it.
struct SegmentSpanTest {
  const Vec2& origin;
  const Vec2* dirs;
  double* out;
  const Vec2& a;
  const Vec2& b;
  const Vec2& e;
  void one(int k) const { out[k] = ray_segment_hit(origin, dirs[k], a, b, e, out[k]); }
  void operator()(int k0, int k1) const {
    int k = k0;
#if defined(__SSE2__)
    const Vec2 w = a - origin;
    const __m128d ex = _mm_set1_pd(e.x()), ey = _mm_set1_pd(e.y());
    const __m128d wx = _mm_set1_pd(w.x()), wy = _mm_set1_pd(w.y());
    const __m128d num_t = _mm_set1_pd(cross(w, e)), parallel = _mm_set1_pd(1e-15);
    const __m128d zero = _mm_setzero_pd(), sign = _mm_set1_pd(-0.0);
    const __m128d u_lo = _mm_set1_pd(-kSegmentEndSlack), u_hi = _mm_set1_pd(1.0 + kSegmentEndSlack);
    for (; k < k1; k += 2) {
      const __m128d d0 = _mm_loadu_pd(dirs[k].data()), d1 = _mm_loadu_pd(dirs[k + 1].data());
      const __m128d dx = _mm_unpacklo_pd(d0, d1), dy = _mm_unpackhi_pd(d0, d1);
      const __m128d denom = _mm_sub_pd(_mm_mul_pd(dx, ey), _mm_mul_pd(dy, ex));
      if (_mm_movemask_pd(_mm_cmplt_pd(_mm_andnot_pd(sign, denom), parallel)) != 0) {
        one(k);
        one(k + 1);
        continue;
      }
      const __m128d t = _mm_div_pd(num_t, denom);
      const __m128d u = _mm_div_pd(_mm_sub_pd(_mm_mul_pd(wx, dy), _mm_mul_pd(wy, dx)), denom);
      double* r = out + k;
      const __m128d best = _mm_loadu_pd(r);
      const __m128d take = _mm_and_pd(_mm_and_pd(_mm_cmpge_pd(t, zero), _mm_cmplt_pd(t, best)),
                                      _mm_and_pd(_mm_cmpnlt_pd(u, u_lo), _mm_cmpngt_pd(u, u_hi)));
      _mm_storeu_pd(r, _mm_or_pd(_mm_and_pd(take, t), _mm_andnot_pd(take, best)));
    }
#endif
    for (; k <= k1; ++k) one(k);
  }
};

// Beam k's hit on a disc, kept when nearer than out[k].
struct CircleBeamTest {
  const Vec2& origin;
  const Vec2* dirs;
  double* out;
  const Circle& circle;
  void operator()(int k) const { out[k] = ray_circle_hit(origin, dirs[k], circle, out[k]); }
};

// The beams of an even fan from `origin` against one obstacle at a time, each tested only
// against the beams its angular extent covers, lowering out[k] to each hit. Obstacles closer
// than `near` to the origin are tested against every beam: their angular extent is
// ill-conditioned. Beyond it, a beam outside an extent by kFanMargin passes the obstacle at
// least near * kFanMargin away, far above the ray test's rounding.
class ObstacleFan {
 public:
  ObstacleFan(const Vec2& origin, std::span<const Vec2> dirs, std::span<double> out,
              const FanLayout& fan, double near, double reach)
      : origin_(origin),
        dirs_(dirs.data()),
        out_(out.data()),
        n_(fan.n),
        near_(near),
        reach_(reach),
        reach2_(reach * reach),
        cone_(fan, 0.0) {}  // beams and obstacles both in the world frame

  double reach() const { return reach_; }
  double reach2() const { return reach2_; }

  // Whether segment a + [0, 1] e, solid on `side` (see seen_from_solid_side), may be hit: it
  // faces the origin, and it is not wholly beyond reach (both ends are, and so is the line or
  // the foot of the perpendicular falls outside the segment). No branch: a fan asks this of
  // every segment near it, and which ones pass follows no pattern a predictor could learn.
  [[gnu::always_inline]] bool may_hit(const Vec2& a, const Vec2& e, double side) const {
    const Vec2 pa = a - origin_;
    const double cr = cross(pa, e);  // |e| times the distance from the origin to the line
    const Vec2 pb = pa + e;
    const double len2 = e.squaredNorm();
    const double foot = -pa.dot(e);  // len2 times the foot's position along the segment
    const bool beyond = (std::min(pa.squaredNorm(), pb.squaredNorm()) > reach2_) &
                        ((foot < 0.0) | (foot > len2) | (cr * cr > reach2_ * len2));
    return !(side * cr > 0.0) & !beyond;
  }

  // Segment [a, b] with edge e = b - a, one that may_hit.
  [[gnu::always_inline]] void segment(const Vec2& a, const Vec2& e, const Vec2& b) const {
    const Vec2 pa = a - origin_;
    const double cr = cross(pa, e);
    const SegmentSpanTest test{origin_, dirs_, out_, a, b, e};
    const Vec2 pb = pa + e;
    const double len2 = e.squaredNorm();
    if (!(cr * cr >= near_ * near_ * len2) || len2 == 0.0) return test(0, n_ - 1);
    if (cr < 0.0) {  // b lies clockwise of a
      cone_.for_spans(pb.x(), pb.y(), pa.x(), pa.y(), test);
    } else {
      cone_.for_spans(pa.x(), pa.y(), pb.x(), pb.y(), test);
    }
  }

  [[gnu::always_inline]] void circle(const Circle& c) const {
    const CircleBeamTest test{origin_, dirs_, out_, c};
    const Vec2 pc = c.center - origin_;
    const double dist = pc.norm();
    if (!(dist > c.radius + near_)) return all_beams(test);
    if (dist - c.radius > reach_) return;
    const double half = std::asin(c.radius / dist);
    cone_.for_beams_about(pc.x(), pc.y(), half, test);
  }

 private:
  template <class Test>
  void all_beams(const Test& test) const {
    for (int k = 0; k < n_; ++k) test(k);
  }

  const Vec2 origin_;
  const Vec2* dirs_;
  double* out_;
  int n_;
  double near_, reach_, reach2_;
  fan_detail::FanCone cone_;
};

}  // namespace

void World::cast_fan(const Vec2& origin, std::span<const Vec2> dirs, std::span<const double> angles,
                     double max_range, std::span<double> out, FanScratch& scratch,
                     bool spacing_known) const {
  if (inside_solid_shape(origin)) {
    std::fill(out.begin(), out.end(), 0.0);
    return;
  }
  cast_fan_from_free(origin, dirs, angles, max_range, out, scratch, spacing_known);
}

void World::cast_fan(const Vec2& origin, std::span<const Vec2> dirs, std::span<const double> angles,
                     double max_range, std::span<double> out) const {
  FanScratch scratch;
  cast_fan(origin, dirs, angles, max_range, out, scratch);
}

// Compiled for x86-64-v3 too (isa_clones.hpp: the same bits): VEX's three-operand forms spare
// the beam tests' register copies.
FLOORNAV_ISA_CLONES
void World::cast_fan_from_free(const Vec2& origin, std::span<const Vec2> dirs,
                               std::span<const double> angles, double max_range,
                               std::span<double> out, FanScratch& scratch,
                               bool spacing_known) const {
  const std::size_t n = dirs.size();
  if (segments_.empty() && circles_.empty()) {
    // cast_ray_from_free is then min(max_range, the grid's cast_ray).
    if (grid_ == nullptr) {
      std::fill(out.begin(), out.end(), max_range);
      return;
    }
    grid_->cast_fan(origin, dirs, angles, max_range, out, scratch);
    at_most(max_range, out);
    return;
  }
  std::optional<FanLayout> fan;
  if (n >= 2 && (!segments_.empty() || !circles_.empty()) && is_finite(origin) &&
      max_range >= 0.0 && std::isfinite(max_range))
    fan = even_fan(angles, spacing_known);
  if (!fan) {
    for (std::size_t i = 0; i < n; ++i) out[i] = cast_ray_from_free(origin, dirs[i], max_range);
    return;
  }
  // What cast_ray_from_free starts from; then the minimum over every obstacle that may be hit
  // within max_range, which does not depend on the order (each test keeps the smaller value).
  if (grid_ != nullptr) {
    grid_->cast_fan(origin, dirs, angles, max_range, out, scratch);
    at_most(max_range, out);
  } else {
    std::fill(out.begin(), out.end(), max_range);
  }

  // Obstacles closer than `near` to the origin are tested against every beam (ObstacleFan).
  const double scale = 1.0 + std::max(std::abs(origin.x()), std::abs(origin.y())) + max_range;
  const double near = 1e-6 * scale;
  const ObstacleFan obstacles(origin, dirs, out, *fan, near, max_range + near);
  const double reach = obstacles.reach(), reach2 = obstacles.reach2();
  const Index& ix = index_;
  const int x0 = cell_x(origin.x() - reach), x1 = cell_x(origin.x() + reach);
  const int y0 = cell_y(origin.y() - reach), y1 = cell_y(origin.y() + reach);
  const std::size_t n_segments = segments_.size();
  std::uint32_t epoch = 0;
  std::uint32_t* entries = nullptr;
  std::uint32_t* mark = fresh_marks(n_segments + circles_.size(), n_segments, epoch, entries);
  // The segments listed in the cells about the origin, each once (marked), gathered, then kept
  // when they may be hit, then tested: no branch per segment until the last step. A row's cells
  // are consecutive in the index, so a row's entries are one run; the square's corner cells
  // beyond reach add segments that may_hit drops.
  const std::uint32_t* offsets = ix.segment_offsets.data();
  const std::uint32_t* items = ix.segment_items.data();
  std::size_t gathered = 0;
  for (int y = y0; y <= y1; ++y) {
    const auto row = static_cast<std::size_t>(y) * ix.nx;
    for (std::uint32_t k = offsets[row + x0], end = offsets[row + x1 + 1]; k < end; ++k) {
      const std::uint32_t id = items[k];
      entries[gathered] = k;
      gathered += mark[id] != epoch;
      mark[id] = epoch;
    }
  }
  const SegmentRay* rays = ix.segment_rays.data();
  const double* sides = ix.segment_sides.data();
  std::size_t kept = 0;
  for (std::size_t j = 0; j < gathered; ++j) {
    const std::uint32_t k = entries[j];
    entries[kept] = k;
    kept += obstacles.may_hit(rays[k].a, rays[k].e, sides[k]);
  }
  for (std::size_t j = 0; j < kept; ++j) {
    const std::uint32_t k = entries[j];
    obstacles.segment(rays[k].a, rays[k].e, segments_[items[k]].b);
  }
  for (int y = y0; !circles_.empty() && y <= y1; ++y) {
    // Distance from the origin to the row's span of y, then to each cell: a cell wholly beyond
    // reach holds no hit before max_range (such a hit lies in a cell that is within reach, and
    // an obstacle is listed in every cell it crosses).
    const double cy0 = ix.origin.y() + y * ix.cell;
    const double gy = std::max({0.0, cy0 - origin.y(), origin.y() - (cy0 + ix.cell)});
    for (int x = x0; x <= x1; ++x) {
      const double cx0 = ix.origin.x() + x * ix.cell;
      const double gx = std::max({0.0, cx0 - origin.x(), origin.x() - (cx0 + ix.cell)});
      if (gx * gx + gy * gy > reach2) continue;
      const auto c = static_cast<std::size_t>(y) * ix.nx + x;
      for (std::uint32_t k = ix.circle_offsets[c]; k < ix.circle_offsets[c + 1]; ++k) {
        const std::uint32_t id = ix.circle_items[k];
        if (mark[n_segments + id] == epoch) continue;
        mark[n_segments + id] = epoch;
        obstacles.circle(circles_[id]);
      }
    }
  }
  // Equal hits have equal bits, so the minimum does not depend on the order of the tests, with
  // one exception: +0 and -0 (an origin on a surface). Which zero cast_ray returns depends on
  // its walk's order, so such beams are cast again by the walk (rare).
  if (!any_zero(out)) return;
  for (std::size_t i = 0; i < n; ++i)
    if (out[i] == 0.0) out[i] = cast_ray_from_free(origin, dirs[i], max_range);
}

}  // namespace floornav
