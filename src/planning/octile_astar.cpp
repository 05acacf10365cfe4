#include "floornav/planning/octile_astar.hpp"

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>

#include "best_first_search.hpp"

namespace floornav {
namespace {

/// Octile A*'s successors: the eight neighbours, each reached through a free cell, diagonals not
/// cutting a corner.
class OctileNeighbours {
 public:
  explicit OctileNeighbours(const FreeRaster& raster)
      : raster_(raster), free_(raster.free.data()), width_(raster.width), height_(raster.height) {
    const std::ptrdiff_t sw = raster.width;
    step_ = {1, -1, sw, -sw, sw + 1, -sw + 1, sw - 1, -sw - 1};
  }

  template <class Relax>
  __attribute__((always_inline)) void operator()(std::size_t u, int ux, int uy, std::int32_t,
                                                 Relax& relax) const {
    // Neighbour u + step_[k] (k < 4 straight, else diagonal) of length kLength[k] (a load, not a
    // branch on the direction); the order of the relaxations does not matter (each pair once).
    // Tables in the function, not static members: indexing those takes two of the search loop's
    // registers (BM_FloorOptimumAstar's instructions under callgrind decide this).
    constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
    constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    constexpr double kLength[8] = {1.0, 1.0, 1.0, 1.0, kSqrt2, kSqrt2, kSqrt2, kSqrt2};
    auto move = [&](int k) __attribute__((always_inline)) {
      relax(u + static_cast<std::size_t>(step_[static_cast<std::size_t>(k)]), kDx[k], kDy[k],
            [&] { return kLength[k]; });
    };
    if (ux > 0 && uy > 0 && ux + 1 < width_ && uy + 1 < height_) {
      // Away from the raster's border every neighbour exists: the moves as a bit mask of the
      // 3 x 3 block, without bounds checks or a branch per neighbour.
      const std::ptrdiff_t sw = width_;
      const std::uint8_t* c = free_ + u;
      const unsigned e = c[1] != 0, west = c[-1] != 0, n = c[sw] != 0, south = c[-sw] != 0;
      unsigned moves = e | west << 1 | n << 2 | south << 3 | (e & n & (c[sw + 1] != 0)) << 4 |
                       (e & south & (c[-sw + 1] != 0)) << 5 | (west & n & (c[sw - 1] != 0)) << 6 |
                       (west & south & (c[-sw - 1] != 0)) << 7;
      for (; moves != 0; moves &= moves - 1) move(std::countr_zero(moves));
      return;
    }
    for (int k = 0; k < 8; ++k) {
      if (!raster_.is_free(ux + kDx[k], uy + kDy[k])) continue;
      if (k >= 4 && (!raster_.is_free(ux + kDx[k], uy) || !raster_.is_free(ux, uy + kDy[k])))
        continue;  // no corner cutting
      move(k);
    }
  }

 private:
  const FreeRaster& raster_;
  // Copies, so that the search's stores cannot be taken to change them.
  const std::uint8_t* free_;
  int width_, height_;
  std::array<std::ptrdiff_t, 8> step_;
};

/// Octile A* (run_octile_search over every neighbour).
bool run_octile_astar(SearchBuffers& b, const FreeRaster& raster, GridCell start, GridCell goal,
                      GridPath& path, std::size_t& expanded) {
  return run_octile_search(b, raster, start, goal, OctileNeighbours(raster), path, expanded);
}

}  // namespace

std::optional<GridPath> octile_astar(const FreeRaster& raster, GridCell start, GridCell goal) {
  thread_local SearchBuffers buffers;  // a batch's thousands of searches allocate nothing
  GridPath path;
  std::size_t expanded = 0;
  if (!run_octile_astar(buffers, raster, start, goal, path, expanded)) return std::nullopt;
  return path;
}

struct GridSearch::Buffers : SearchBuffers {};

GridSearch::GridSearch() : buffers_(std::make_unique<Buffers>()) {}
GridSearch::~GridSearch() = default;
GridSearch::GridSearch(GridSearch&&) noexcept = default;
GridSearch& GridSearch::operator=(GridSearch&&) noexcept = default;

bool GridSearch::search(const FreeRaster& raster, GridCell start, GridCell goal, GridPath& path) {
  return run_octile_astar(*buffers_, raster, start, goal, path, expanded_);
}

}  // namespace floornav
