#include "floornav/nav/rolling_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace floornav {

namespace {
int floor_div(double v, double cell) {
  return static_cast<int>(std::floor(std::clamp(v / cell, -1e9, 1e9)));
}
int mod(int a, int n) {
  const int r = a % n;
  return r < 0 ? r + n : r;
}
}  // namespace

RollingGrid::RollingGrid(double cell, int side, double decay, const Vec2& centre)
    : cell_(cell), side_(side), decay_(decay) {
  if (!(cell > 0.0) || side < 4 || !(decay > 0.0))
    throw std::invalid_argument("rolling grid: need cell > 0, side >= 4 and decay > 0");
  const std::size_t n = static_cast<std::size_t>(side) * static_cast<std::size_t>(side);
  evidence_.assign(n, 0);
  updated_.assign(n, 0.0f);
  scan_.assign(n, 0);
  hit_x_.assign(n, 0.0f);
  hit_y_.assign(n, 0.0f);
  const GridCell c = cell_of(centre);
  origin_ = {c.x - side_ / 2, c.y - side_ / 2};
}

GridCell RollingGrid::cell_of(const Vec2& p) const {
  return {floor_div(p.x(), cell_), floor_div(p.y(), cell_)};
}

std::size_t RollingGrid::slot(GridCell c) const {
  return static_cast<std::size_t>(mod(c.y, side_)) * static_cast<std::size_t>(side_) +
         static_cast<std::size_t>(mod(c.x, side_));
}

int RollingGrid::decayed(std::size_t i, double t) const {
  const int e = evidence_[i];
  if (e == 0) return 0;
  const double age = t - static_cast<double>(updated_[i]);
  const int fade = age > 0.0 ? static_cast<int>(std::min(age / decay_, 16.0)) : 0;
  const int mag = std::max(0, std::abs(e) - fade);
  return e > 0 ? mag : -mag;
}

int RollingGrid::evidence(GridCell c, double t) const {
  return in_window(c) ? decayed(slot(c), t) : 0;
}

std::size_t RollingGrid::occupied_count(double t) const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < evidence_.size(); ++i)
    if (evidence_[i] >= kOccupied && decayed(i, t) >= kOccupied) ++n;
  return n;
}

void RollingGrid::clear() {
  std::fill(evidence_.begin(), evidence_.end(), 0);
}

void RollingGrid::forget_column(int gx) {
  const std::size_t x = static_cast<std::size_t>(mod(gx, side_));
  for (int y = 0; y < side_; ++y)
    evidence_[static_cast<std::size_t>(y) * static_cast<std::size_t>(side_) + x] = 0;
}

void RollingGrid::forget_row(int gy) {
  const auto row = evidence_.begin() + static_cast<std::ptrdiff_t>(mod(gy, side_)) * side_;
  std::fill(row, row + side_, 0);
}

void RollingGrid::follow(const Vec2& p) {
  const GridCell c = cell_of(p);
  const GridCell centre{origin_.x + side_ / 2, origin_.y + side_ / 2};
  if (std::abs(c.x - centre.x) <= side_ / 4 && std::abs(c.y - centre.y) <= side_ / 4) return;
  const GridCell next{c.x - side_ / 2, c.y - side_ / 2};
  const int dx = next.x - origin_.x, dy = next.y - origin_.y;
  if (std::abs(dx) >= side_ || std::abs(dy) >= side_) {
    clear();
  } else {
    // The columns (rows) that leave the window are the ones the new cells will reuse.
    for (int k = 0; k < std::abs(dx); ++k)
      forget_column(dx > 0 ? origin_.x + k : origin_.x + side_ - 1 - k);
    for (int k = 0; k < std::abs(dy); ++k)
      forget_row(dy > 0 ? origin_.y + k : origin_.y + side_ - 1 - k);
  }
  origin_ = next;
}

void RollingGrid::pass(GridCell c, double t) {
  const std::size_t i = slot(c);
  const std::uint32_t stamp = 2 * scan_count_;
  if (scan_[i] >= stamp) return;  // once a scan
  evidence_[i] = static_cast<std::int8_t>(std::max(kMinEvidence, decayed(i, t) - 1));
  updated_[i] = static_cast<float>(t);
  scan_[i] = stamp;
}

void RollingGrid::hit(GridCell c, const Vec2& p, double t) {
  const std::size_t i = slot(c);
  const std::uint32_t stamp = 2 * scan_count_ + 1;
  hit_x_[i] = static_cast<float>(p.x());
  hit_y_[i] = static_cast<float>(p.y());
  if (scan_[i] == stamp) return;  // once a scan (the latest return point is kept)
  // A pass of this scan already took one off; a return overrides it.
  const int e = scan_[i] == stamp - 1 ? evidence_[i] + 1 : decayed(i, t);
  evidence_[i] = static_cast<std::int8_t>(std::min(kMaxEvidence, std::max(e, 0) + kHitGain));
  updated_[i] = static_cast<float>(t);
  scan_[i] = stamp;
}

void RollingGrid::update(std::span<const SensorBeam> beams, std::span<const double> ranges,
                         std::span<const RangeSensorSpec> sensors, double sense_range, double t) {
  ++scan_count_;
  if (scan_count_ >= std::numeric_limits<std::uint32_t>::max() / 2 - 1) {
    std::fill(scan_.begin(), scan_.end(), 0);
    scan_count_ = 1;
  }
  const std::size_t n = std::min({beams.size(), ranges.size(), sensors.size()});
  // Pass 1: every beam clears the cells it crosses before its end cell.
  for (std::size_t b = 0; b < n; ++b) {
    const double reach = std::min(ranges[b], std::min(sense_range, sensors[b].max_range));
    if (!(reach > 0.0)) continue;
    const Vec2 o = beams[b].origin, d = beams[b].dir;
    GridCell c = cell_of(o);
    const GridCell end = cell_of(o + d * reach);
    // Amanatides-Woo walk, in cell units.
    const double ox = o.x() / cell_, oy = o.y() / cell_;
    const int sx = d.x() > 0.0 ? 1 : -1, sy = d.y() > 0.0 ? 1 : -1;
    constexpr double kInf = std::numeric_limits<double>::infinity();
    const double tdx = d.x() != 0.0 ? std::abs(1.0 / d.x()) : kInf;
    const double tdy = d.y() != 0.0 ? std::abs(1.0 / d.y()) : kInf;
    double tx = d.x() != 0.0 ? (sx > 0 ? (c.x + 1 - ox) : (ox - c.x)) * tdx : kInf;
    double ty = d.y() != 0.0 ? (sy > 0 ? (c.y + 1 - oy) : (oy - c.y)) * tdy : kInf;
    const int max_steps = std::abs(end.x - c.x) + std::abs(end.y - c.y);
    for (int k = 0; k < max_steps && !(c == end); ++k) {
      if (!in_window(c)) break;  // the window is convex: a beam that left it stays out
      pass(c, t);
      if (tx < ty) {
        c.x += sx;
        tx += tdx;
      } else {
        c.y += sy;
        ty += tdy;
      }
    }
  }
  // Pass 2: returns mark their end cells.
  for (std::size_t b = 0; b < n; ++b) {
    const double limit = std::min(sense_range, sensors[b].max_range);
    if (!(ranges[b] < limit)) continue;
    const Vec2 p = beams[b].origin + beams[b].dir * ranges[b];
    const GridCell c = cell_of(p);
    if (in_window(c)) hit(c, p, t);
  }
}

void RollingGrid::inflate(double radius, double t, FreeRaster& out) const {
  out.width = side_;
  out.height = side_;
  out.free.assign(static_cast<std::size_t>(side_) * static_cast<std::size_t>(side_), 1);
  const int reach = static_cast<int>(std::ceil(radius / cell_)) + 1;
  const double r2 = radius * radius;
  for (int y = 0; y < side_; ++y)
    for (int x = 0; x < side_; ++x) {
      const GridCell g{origin_.x + x, origin_.y + y};
      const std::size_t i = slot(g);
      if (evidence_[i] < kOccupied || decayed(i, t) < kOccupied) continue;
      const double px = hit_x_[i], py = hit_y_[i];
      for (int j = std::max(0, y - reach); j <= std::min(side_ - 1, y + reach); ++j) {
        const double cy = (origin_.y + j + 0.5) * cell_ - py;
        for (int k = std::max(0, x - reach); k <= std::min(side_ - 1, x + reach); ++k) {
          const double cx = (origin_.x + k + 0.5) * cell_ - px;
          if (cx * cx + cy * cy < r2)
            out.free[static_cast<std::size_t>(j) * static_cast<std::size_t>(side_) +
                     static_cast<std::size_t>(k)] = 0;
        }
      }
    }
}

std::size_t RollingGrid::remembered_points(const Vec2& p, double range, double t,
                                           std::span<Vec2> out) const {
  std::size_t n = 0;
  const GridCell lo = cell_of(p - Vec2(range, range)), hi = cell_of(p + Vec2(range, range));
  const double r2 = range * range;
  for (int y = std::max(lo.y, origin_.y); y <= std::min(hi.y, origin_.y + side_ - 1); ++y)
    for (int x = std::max(lo.x, origin_.x); x <= std::min(hi.x, origin_.x + side_ - 1); ++x) {
      const std::size_t i = slot({x, y});
      if (evidence_[i] < kOccupied || decayed(i, t) < kOccupied) continue;
      const Vec2 q(hit_x_[i], hit_y_[i]);
      if ((q - p).squaredNorm() > r2) continue;
      if (n == out.size()) return n;
      out[n++] = q;
    }
  return n;
}

}  // namespace floornav
