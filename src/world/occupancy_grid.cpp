#include "floornav/world/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

// The grid itself: its cells, its frame, its extent. What it computes once and the queries:
// the distance transform and clearance (grid_distance_transform.cpp), the ray walk
// (grid_ray.cpp), fans of rays (grid_fan.cpp).

namespace floornav {
namespace {

/// Largest grid the int32 cell indices (and the 2 * row + 1 column code) can address.
constexpr std::size_t kMaxCells = std::size_t{1} << 30;

}  // namespace

OccupancyGrid::OccupancyGrid(int width, int height, double resolution, Pose2 origin,
                             std::vector<std::uint8_t> occupied)
    : width_(width),
      height_(height),
      resolution_(resolution),
      origin_(origin),
      occupied_(std::move(occupied)) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("OccupancyGrid: width and height must be positive, got " +
                                std::to_string(width) + " x " + std::to_string(height));
  }
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw std::invalid_argument("OccupancyGrid: resolution must be positive and finite, got " +
                                std::to_string(resolution));
  }
  if (!origin.is_finite()) throw std::invalid_argument("OccupancyGrid: origin is not finite");
  const std::size_t cells = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (cells > kMaxCells) {
    throw std::invalid_argument("OccupancyGrid: " + std::to_string(cells) +
                                " cells is more than the 2^30 supported");
  }
  if (occupied_.size() != cells) {
    throw std::invalid_argument("OccupancyGrid: expected " + std::to_string(cells) +
                                " cells (width * height), got " + std::to_string(occupied_.size()));
  }
  occupied_count_ = static_cast<std::size_t>(
      std::count_if(occupied_.begin(), occupied_.end(), [](std::uint8_t c) { return c != 0; }));
  cos_yaw_ = std::cos(origin_.theta);
  sin_yaw_ = std::sin(origin_.theta);
  compute_distance_transform();
  compute_boundary();
}

bool OccupancyGrid::occupied(int ix, int iy) const {
  if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return false;
  return occupied_[static_cast<std::size_t>(iy) * width_ + ix] != 0;
}

std::size_t OccupancyGrid::occupied_count() const {
  return occupied_count_;
}

Vec2 OccupancyGrid::to_grid(const Vec2& world) const {
  const double dx = world.x() - origin_.position.x();
  const double dy = world.y() - origin_.position.y();
  return {cos_yaw_ * dx + sin_yaw_ * dy, -sin_yaw_ * dx + cos_yaw_ * dy};
}

Vec2 OccupancyGrid::to_world(const Vec2& grid) const {
  return {origin_.position.x() + cos_yaw_ * grid.x() - sin_yaw_ * grid.y(),
          origin_.position.y() + sin_yaw_ * grid.x() + cos_yaw_ * grid.y()};
}

void OccupancyGrid::world_extent(Vec2* min, Vec2* max) const {
  const double w = width_ * resolution_;
  const double h = height_ * resolution_;
  const Vec2 corners[4] = {to_world({0.0, 0.0}), to_world({w, 0.0}), to_world({0.0, h}),
                           to_world({w, h})};
  *min = corners[0];
  *max = corners[0];
  for (const Vec2& c : corners) {
    *min = min->cwiseMin(c);
    *max = max->cwiseMax(c);
  }
}

}  // namespace floornav
