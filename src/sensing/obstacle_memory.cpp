#include "floornav/sensing/obstacle_memory.hpp"

#include <algorithm>

namespace floornav {

std::size_t ObstacleMemory::update(std::span<const Vec2> points, double t, double lifetime,
                                   double merge_radius, std::span<Vec2> out) {
  // Forget old points, keeping order (oldest first) so that eviction drops the oldest.
  int kept = 0;
  for (int i = 0; i < count_; ++i) {
    if (t - times_[i] <= lifetime) {
      points_[kept] = points_[i];
      times_[kept] = times_[i];
      ++kept;
    }
  }
  count_ = kept;
  const double r2 = merge_radius * merge_radius;
  for (const Vec2& p : points) {
    int match = -1;
    for (int i = 0; i < count_; ++i)
      if ((points_[i] - p).squaredNorm() <= r2) {
        match = i;
        break;
      }
    if (match >= 0) {
      // Move the refreshed point to the young end.
      for (int i = match; i + 1 < count_; ++i) {
        points_[i] = points_[i + 1];
        times_[i] = times_[i + 1];
      }
      --count_;
    } else if (count_ == kCapacity) {
      for (int i = 0; i + 1 < count_; ++i) {
        points_[i] = points_[i + 1];
        times_[i] = times_[i + 1];
      }
      --count_;
    }
    points_[count_] = p;
    times_[count_] = t;
    ++count_;
  }
  const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(count_), out.size());
  for (std::size_t i = 0; i < n; ++i) out[i] = points_[i];
  return n;
}

}  // namespace floornav
