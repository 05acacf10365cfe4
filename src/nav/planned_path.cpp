#include "floornav/nav/planned_path.hpp"

#include <algorithm>
#include <limits>

namespace floornav {

void PlannedPath::assign(std::span<const Vec2> points) {
  points_.assign(points.begin(), points.end());
  arc_.resize(points_.size());
  double s = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    if (i > 0) s += (points_[i] - points_[i - 1]).norm();
    arc_[i] = s;
  }
  segment_ = 0;
  s_ = 0.0;
}

void PlannedPath::clear() {
  points_.clear();
  arc_.clear();
  segment_ = 0;
  s_ = 0.0;
}

double PlannedPath::project(const Vec2& p, double ahead) {
  if (points_.empty()) return std::numeric_limits<double>::infinity();
  if (points_.size() == 1) return (p - points_[0]).norm();
  double best = std::numeric_limits<double>::infinity();
  std::size_t best_seg = segment_;
  double best_s = s_;
  const double limit = s_ + ahead;
  for (std::size_t i = segment_; i + 1 < points_.size() && arc_[i] <= limit; ++i) {
    const Vec2 a = points_[i], d = points_[i + 1] - a;
    const double len2 = d.squaredNorm();
    double u = len2 > 0.0 ? (p - a).dot(d) / len2 : 0.0;
    u = std::clamp(u, 0.0, 1.0);
    double s = arc_[i] + u * (arc_[i + 1] - arc_[i]);
    if (i == segment_ && s < s_) {  // never backwards along the current segment
      s = s_;
      u = len2 > 0.0 ? (s_ - arc_[i]) / (arc_[i + 1] - arc_[i]) : 0.0;
    }
    const double dist = (p - (a + u * d)).norm();
    if (dist < best) {
      best = dist;
      best_seg = i;
      best_s = s;
    }
  }
  segment_ = best_seg;
  s_ = best_s;
  return best;
}

Vec2 PlannedPath::point_at(double s) const {
  if (points_.empty()) return Vec2::Zero();
  if (s <= 0.0) return points_.front();
  if (s >= arc_.back()) return points_.back();
  const auto it = std::upper_bound(arc_.begin(), arc_.end(), s);
  const std::size_t i = static_cast<std::size_t>(it - arc_.begin()) - 1;
  const double len = arc_[i + 1] - arc_[i];
  const double u = len > 0.0 ? (s - arc_[i]) / len : 0.0;
  return points_[i] + u * (points_[i + 1] - points_[i]);
}

Vec2 PlannedPath::subgoal(const Vec2& p, double lookahead, double corner) const {
  if (points_.empty()) return p;
  const std::size_t last = points_.size() - 1;
  std::size_t next = std::min(segment_ + 1, last);
  if (next < last && (p - points_[next]).norm() <= corner) ++next;
  return point_at(std::min(s_ + lookahead, arc_[next]));
}

}  // namespace floornav
