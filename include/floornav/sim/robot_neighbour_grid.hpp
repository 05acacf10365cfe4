#pragma once
/// @file
/// Which robots are near a point: a uniform grid over robot positions in contiguous arrays, built
/// by a counting sort (O(robots + cells), no allocation once sized) and refiled every step, the
/// few robots that changed cell moved in place. Robots outside the grid's box are kept in its
/// border cells, so no robot is ever lost.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "floornav/geometry/vec2.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

class RobotNeighbourGrid {
 public:
  /// Sizes the grid over `box` with square cells of at least `cell` metres for up to `robots`
  /// robots; cells grow as needed to keep their number near the robots' (memory stays O(robots)).
  void reset(const Box2& box, double cell, std::size_t robots);

  /// Files robot i at positions[i] when present[i] is non-zero. positions.size() <= robots.
  void build(std::span<const Vec2> positions, std::span<const std::uint8_t> present);

  /// The cell `refile` takes for a robot at `p` (robots outside the box: its border cell).
  std::uint32_t cell_index(const Vec2& p) const { return static_cast<std::uint32_t>(cell_of(p)); }

  /// Files robot i in cells[i] (its `cell_index`) when present[i] is non-zero, with the same
  /// robots present as at the last `build`: the grid `build` would make, but a robot that kept
  /// its cell costs one comparison (robots cross a cell's edge every few dozen steps).
  void refile(std::span<const std::uint32_t> cells, std::span<const std::uint8_t> present);

  /// Calls f(j) for every filed robot j whose cell overlaps the square of half-width `radius`
  /// around `p` (a superset of those within `radius`; the caller measures the distance).
  template <class F>
  void for_each_near(const Vec2& p, double radius, F&& f) const {
    const int x0 = cell_x(p.x() - radius), x1 = cell_x(p.x() + radius);
    const int y0 = cell_y(p.y() - radius), y1 = cell_y(p.y() + radius);
    for (int y = y0; y <= y1; ++y) {
      const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(nx_);
      const std::uint32_t begin = start_[row + static_cast<std::size_t>(x0)];
      const std::uint32_t end = start_[row + static_cast<std::size_t>(x1) + 1];
      for (std::uint32_t k = begin; k < end; ++k) f(static_cast<std::size_t>(items_[k]));
    }
  }

  double cell_size() const { return cell_; }

 private:
  // Inline: every neighbour query takes four of them.
  int cell_x(double x) const { return clamp_cell((x - origin_.x()) * inv_cell_, nx_); }
  int cell_y(double y) const { return clamp_cell((y - origin_.y()) * inv_cell_, ny_); }
  // floor(c) clamped to [0, n - 1], without floor's call on baseline x86-64: below n - 1 and
  // not below 0, floor is the truncation (NaN takes cell 0).
  static int clamp_cell(double c, int n) {
    if (!(c >= 0.0)) return 0;
    if (c >= static_cast<double>(n - 1)) return n - 1;
    return static_cast<int>(c);
  }
  std::size_t cell_of(const Vec2& p) const {
    return static_cast<std::size_t>(cell_y(p.y())) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(cell_x(p.x()));
  }

  // The counting sort of present robots by cell_of_robot_ (robots 0 .. present.size() - 1).
  void sort_into_cells(std::span<const std::uint8_t> present);
  void move_robot(std::uint32_t robot, std::uint32_t from, std::uint32_t to);

  Vec2 origin_{Vec2::Zero()};
  double cell_{1.0};
  double inv_cell_{1.0};
  int nx_{1};
  int ny_{1};
  std::vector<std::uint32_t> start_;  ///< robots of cell c: items_[start_[c] .. start_[c + 1])
  std::vector<std::uint32_t> items_;
  std::vector<std::uint32_t> cell_of_robot_;
  std::vector<std::uint32_t> moved_;  ///< refile's robots that changed cell
};

}  // namespace floornav
