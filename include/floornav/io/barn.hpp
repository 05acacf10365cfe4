#pragma once
/// @file
/// The BARN benchmark (Perille et al., SSRR 2020; the BARN challenge): its reference paths
/// (`path_N.npy`, cells of the 30 x 30 grid) and the optimal time the challenge scores against.

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

#include "floornav/geometry/vec2.hpp"

namespace floornav {

/// Reads a NumPy .npy file holding an (n, 2) array of little-endian int64 (dtype '<i8', C order).
/// The header is read strictly (exactly descr, fortran_order and shape; a 3-D shape, another
/// dtype or data of another length is an error). Throws InputError naming the file.
std::vector<std::array<std::int64_t, 2>> load_npy_int_pairs(const std::filesystem::path& path);

/// BARN's grid is 30 x 30 cells.
inline constexpr std::int64_t kBarnGridSize = 30;

/// A BARN reference path (path_N.npy): a non-empty (n, 2) array of cells inside the 30 x 30 grid.
std::vector<std::array<std::int64_t, 2>> load_barn_path(const std::filesystem::path& path);

/// The challenge's cell -> Gazebo transform: x = 0.15 row - 4.575, y = 0.15 col + 5.075.
Vec2 barn_cell_to_world(std::int64_t row, std::int64_t col);

/// The challenge's optimal time: the length of start -> reference path -> goal, at 2 m/s.
double barn_optimal_time(const std::vector<std::array<std::int64_t, 2>>& path, const Vec2& start,
                         const Vec2& goal);

}  // namespace floornav
