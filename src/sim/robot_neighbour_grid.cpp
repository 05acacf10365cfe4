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
  moved_.clear();
  moved_.reserve(robots);
}

void RobotNeighbourGrid::build(std::span<const Vec2> positions,
                               std::span<const std::uint8_t> present) {
  const std::size_t n = positions.size();
  for (std::size_t i = 0; i < n; ++i)
    if (present[i]) cell_of_robot_[i] = cell_index(positions[i]);
  sort_into_cells(present.first(n));
}

void RobotNeighbourGrid::refile(std::span<const std::uint32_t> cells,
                                std::span<const std::uint8_t> present) {
  moved_.clear();
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (present[i] && cells[i] != cell_of_robot_[i])
      moved_.push_back(static_cast<std::uint32_t>(i));
  // A move shifts the starts and the items between its two cells, a vertical one a whole row
  // of them; the counting sort passes three times over the robots and twice over the cells. Take
  // the cheaper: moving in place loses to the sort when many robots cross long rows (100,000
  // robots: rows of 632 cells) and wins for 1,000. BM_Fleet_QuickBotWarehouse/1000 and /100000
  // (bench/fleet_bench.cpp) decide this.
  const std::size_t sort_cost = 3 * cells.size() + 2 * start_.size();
  std::size_t move_cost = 0;
  for (const std::uint32_t i : moved_) {
    const auto [lo, hi] = std::minmax(cell_of_robot_[i], cells[i]);
    move_cost += (hi - lo) + (start_[hi] - start_[lo]);
    if (move_cost > sort_cost) break;
  }
  if (move_cost > sort_cost) {
    for (const std::uint32_t i : moved_) cell_of_robot_[i] = cells[i];
    sort_into_cells(present.first(cells.size()));
    return;
  }
  for (const std::uint32_t i : moved_) {
    move_robot(i, cell_of_robot_[i], cells[i]);
    cell_of_robot_[i] = cells[i];
  }
}

void RobotNeighbourGrid::move_robot(std::uint32_t robot, std::uint32_t from, std::uint32_t to) {
  const auto cell = [&](std::uint32_t c) {
    return std::pair{items_.begin() + start_[c], items_.begin() + start_[c + 1]};
  };
  // Cells keep their robots sorted by index: find the robot in its old cell, and its place in
  // the new one, in the layout before the move.
  const auto [from_begin, from_end] = cell(from);
  const auto at = std::lower_bound(from_begin, from_end, robot);
  const auto [to_begin, to_end] = cell(to);
  const auto place = std::lower_bound(to_begin, to_end, robot);
  if (from < to) {
    // The items between close up over the robot's old place; the cells after `from`, up to and
    // including `to`, begin one item earlier.
    std::move(at + 1, place, at);
    *(place - 1) = robot;
    for (std::uint32_t c = from + 1; c <= to; ++c) --start_[c];
  } else {
    std::move_backward(place, at, at + 1);
    *place = robot;
    for (std::uint32_t c = to + 1; c <= from; ++c) ++start_[c];
  }
}

void RobotNeighbourGrid::sort_into_cells(std::span<const std::uint8_t> present) {
  std::fill(start_.begin(), start_.end(), 0u);
  const std::size_t n = present.size();
  // Count robots per cell (shifted by one), prefix-sum into starts, then place in index order:
  // items within a cell stay sorted by robot index, so every query visits them in one order.
  for (std::size_t i = 0; i < n; ++i)
    if (present[i]) ++start_[cell_of_robot_[i] + 1];
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
