#include "floornav/sim/robot_neighbour_grid.hpp"

#include <algorithm>
#include <cmath>

namespace floornav {

namespace {
// Cells per robot allowed before the cells grow: enough for sparse fleets in big halls, and the
// counting sort's pass over the cells stays as cheap as its pass over the robots.
constexpr double kCellsPerRobot = 4.0;
constexpr double kMinCells = 1024.0;
}  // namespace

void RobotNeighbourGrid::reset(const Box2& box, double cell, std::size_t robots) {
  const Vec2 size = box.size().cwiseMax(Vec2(1e-3, 1e-3));
  cell = std::max(cell, 1e-3);
  const double budget = std::max(kMinCells, kCellsPerRobot * static_cast<double>(robots));
  while ((size.x() / cell + 1.0) * (size.y() / cell + 1.0) > budget) cell *= 1.5;
  cell_ = cell;
  inv_cell_ = 1.0 / cell;
  origin_ = box.min;
  nx_ = static_cast<int>(std::floor(size.x() / cell)) + 1;
  ny_ = static_cast<int>(std::floor(size.y() / cell)) + 1;
  start_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_) + 1, 0);
  items_.assign(robots, 0);
  cell_of_robot_.assign(robots, 0);
}

void RobotNeighbourGrid::build(std::span<const Vec2> positions,
                               std::span<const std::uint8_t> present) {
  std::fill(start_.begin(), start_.end(), 0u);
  const std::size_t n = positions.size();
  // Count robots per cell (shifted by one), prefix-sum into starts, then place in index order:
  // items within a cell stay sorted by robot index, so every query visits them in one order.
  for (std::size_t i = 0; i < n; ++i) {
    if (!present[i]) continue;
    const auto c = static_cast<std::uint32_t>(cell_of(positions[i]));
    cell_of_robot_[i] = c;
    ++start_[c + 1];
  }
  for (std::size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
  for (std::size_t i = 0; i < n; ++i) {
    if (!present[i]) continue;
    items_[start_[cell_of_robot_[i]]++] = static_cast<std::uint32_t>(i);
  }
  // The placing pass advanced each start to the next cell's: shift back by one cell.
  for (std::size_t c = start_.size() - 1; c > 0; --c) start_[c] = start_[c - 1];
  start_[0] = 0;
}

}  // namespace floornav
