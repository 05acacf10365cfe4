#include "floornav/nav/footprint_guard.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "floornav/geometry/polygon.hpp"

namespace floornav {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

// Signed distance from p to the polygon: negative inside.
double signed_gap(std::span<const Vec2> footprint, const Vec2& p) {
  const double d = boundary_distance(footprint, p);
  return contains(footprint, p) ? -d : d;
}

struct Box {
  Vec2 lo, hi;
};
Box bounding_box(std::span<const Vec2> footprint) {
  Box b{footprint[0], footprint[0]};
  for (const Vec2& q : footprint) {
    b.lo = b.lo.cwiseMin(q);
    b.hi = b.hi.cwiseMax(q);
  }
  return b;
}
}  // namespace

double footprint_clearance(std::span<const Vec2> footprint, std::span<const Vec2> points) {
  double best = kInf;
  for (const Vec2& q : points) best = std::min(best, signed_gap(footprint, q));
  return best;
}

double time_to_contact(std::span<const Vec2> footprint, std::span<const Vec2> points, double v,
                       double omega, double horizon, double margin, double step) {
  if (footprint.size() < 3 || points.empty()) return kInf;
  const Box box = bounding_box(footprint);
  double reach = 0.0;  // the farthest footprint point from the centre: its speed bounds all
  for (const Vec2& q : footprint) reach = std::max(reach, q.norm());
  const double speed = std::abs(v) + std::abs(omega) * reach;
  const int samples =
      speed > 0.0 ? std::max(1, static_cast<int>(std::ceil(speed * horizon / step))) : 0;
  for (int k = 0; k <= samples; ++k) {
    const double t = samples > 0 ? horizon * k / samples : 0.0;
    // The pose at t on the arc (the unicycle's exact solution).
    const double th = omega * t;
    const double c = std::cos(th), s = std::sin(th);
    Vec2 p;
    if (std::abs(omega) < 1e-9)
      p = Vec2(v * t, 0.0);
    else
      p = Vec2(v / omega * s, v / omega * (1.0 - c));
    for (const Vec2& q : points) {
      const Vec2 d = q - p;
      const Vec2 local(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
      if (local.x() < box.lo.x() - margin || local.x() > box.hi.x() + margin ||
          local.y() < box.lo.y() - margin || local.y() > box.hi.y() + margin)
        continue;  // outside the inflated bounding box: cannot be within the margin
      if (signed_gap(footprint, local) < margin) return t;
    }
    if (samples == 0) break;
  }
  return kInf;
}

FootprintGuard::FootprintGuard(std::vector<Vec2> footprint, FootprintGuardParams params)
    : footprint_(std::move(footprint)), p_(params) {
  for (const Vec2& q : footprint_) circumradius_ = std::max(circumradius_, q.norm());
  local_.reserve(4096);
}

void FootprintGuard::set_points(const Pose2& pose, std::span<const Vec2> world_points,
                                double reach) {
  pose_ = pose;
  keep_ = circumradius_ + p_.margin + std::max(reach, p_.back_speed) * p_.horizon;
  local_.clear();
  add_points(world_points);
}

void FootprintGuard::add_points(std::span<const Vec2> world_points) {
  const double c = std::cos(pose_.theta), s = std::sin(pose_.theta);
  for (const Vec2& q : world_points) {
    const Vec2 d = q - pose_.position;
    if (d.squaredNorm() > keep_ * keep_) continue;
    local_.emplace_back(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
  }
}

double FootprintGuard::margin_now() const {
  // Already closer than the margin (it drove there, or the point was behind it): any move that
  // keeps at least half of the clearance there is is allowed, so that it can get away.
  const double now = clearance();
  return std::clamp(std::min(p_.margin, 0.5 * now), 0.0, p_.margin);
}

double FootprintGuard::free_fraction(double v, double omega) const {
  const double t = time_to_contact(footprint_, local_, v, omega, p_.horizon, margin_now());
  return std::isinf(t) ? 1.0 : std::clamp(t / p_.horizon, 0.0, 1.0);
}

GuardResult FootprintGuard::check(double v, double omega) const {
  if (local_.empty() || footprint_.size() < 3) return {v, omega, 1.0, false};
  const double m = margin_now();
  auto fraction = [&](double cv, double cw) {
    const double t = time_to_contact(footprint_, local_, cv, cw, p_.horizon, m);
    return std::isinf(t) ? 1.0 : std::clamp(t / p_.horizon, 0.0, 1.0);
  };
  const double s = fraction(v, omega);
  if (s >= 1.0) return {v, omega, 1.0, false};
  if (s >= p_.min_scale) return {s * v, s * omega, s, false};
  // Blocked: the nearest way out. Turning keeps the wanted direction's sign unless that is what
  // is blocked; a wanted command that does not turn tries both.
  const double w = p_.turn_rate;
  const double turn = omega != 0.0 ? (omega > 0.0 ? 1.0 : -1.0) : 1.0;
  const double b = p_.back_speed;
  const std::array<std::array<double, 2>, 7> options{{
      {0.0, -turn * w},  // the other turn direction, on the spot
      {b, 0.0},          // creep straight on
      {-b, 0.0},         // back up straight
      {-b, turn * w},    // back up turning either way
      {-b, -turn * w},
      {b, turn * w},  // creep on turning either way
      {b, -turn * w},
  }};
  GuardResult best{0.0, 0.0, s, true};
  double best_fraction = 0.0, best_distance = kInf;
  for (const auto& [cv, cw] : options) {
    const double f = fraction(cv, cw);
    // The nearest to the wanted command, in units of the alternatives' own speeds.
    const double dist = std::hypot((cv - v) / std::max(b, 1e-9), (cw - omega) / std::max(w, 1e-9));
    if (f > best_fraction + 1e-9 || (f > best_fraction - 1e-9 && f > 0.0 && dist < best_distance)) {
      best_fraction = f;
      best_distance = dist;
      best.v = f * cv;
      best.omega = f * cw;
    }
  }
  if (best_fraction < p_.min_scale && s > best_fraction) {
    // Nothing better than the wanted way, slowed down.
    return {s * v, s * omega, s, false};
  }
  return best;
}

}  // namespace floornav
