#pragma once
// Reading the map images ROS map_server accepts (PGM and PNG) into 8-bit samples. Private to the
// io library.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace floornav::io_detail {

/// Largest grid (in cells) a map may have: 2^26, an 8192 x 8192 map, and at most 2^15 cells on a
/// side. A grid costs about 20 bytes per cell once loaded (the occupancy, the distance transform,
/// the free runs, the free components), and the transform's row pass 28 bytes per column on top:
/// with the side bound too, a map of 2^26 cells needs at most about 1.4 GB, whatever its shape
/// (a 2^26 x 1 map once needed 2.5 GB within the cell limit alone) and whatever its file's size
/// (a 55 kB 1-bit PNG can promise 2^28 pixels). Larger headers are refused before any pixel is
/// read.
inline constexpr std::uint64_t kMaxMapCells = std::uint64_t{1} << 26;
inline constexpr std::uint64_t kMaxMapSide = std::uint64_t{1} << 15;

/// Why a map of `width` x `height` cells is too large ("image of 70000 x 2 pixels is too large
/// (limit 2^26 = 67108864 cells, 32768 on a side)"), or "" when it is not. Each side is compared
/// alone first: their product could wrap around 2^64.
inline std::string map_size_problem(std::uint64_t width, std::uint64_t height, const char* what,
                                    const char* unit) {
  if (width <= kMaxMapSide && height <= kMaxMapSide && width * height <= kMaxMapCells) return "";
  return std::string(what) + " of " + std::to_string(width) + " x " + std::to_string(height) + " " +
         unit + " is too large (limit 2^26 = " + std::to_string(kMaxMapCells) + " cells, " +
         std::to_string(kMaxMapSide) + " on a side)";
}

/// An image as 8-bit samples, row 0 at the top, `channels` (1 = gray, 3 = RGB) per pixel, alpha
/// already dropped.
struct RasterImage {
  int width{0};
  int height{0};
  int channels{1};
  std::vector<std::uint8_t> samples;  ///< width * height * channels, row-major from the top row

  /// Mean of the pixel's channels, 0 (black) .. 255 (white), as map_server computes it.
  double mean(int x, int y) const {
    const std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                           static_cast<std::size_t>(x)) *
                          static_cast<std::size_t>(channels);
    if (channels == 1) return samples[i];
    return (samples[i] + samples[i + 1] + samples[i + 2]) / 3.0;
  }
};

/// Reads a binary (P5) or plain (P2) PGM with any maxval (1..65535, rescaled to 8 bits, rounding
/// to nearest). Throws InputError naming `path`.
RasterImage read_pgm(const std::filesystem::path& path);

/// Reads any PNG libpng can (gray, gray + alpha, RGB, RGBA, palette, each also with a tRNS
/// transparency chunk; 1..16 bits) as 8-bit gray or RGB: 16-bit samples are stripped to their
/// high byte and alpha is dropped, as SDL_image (used by ROS 1 map_server) does. Throws InputError
/// naming `path`.
RasterImage read_png(const std::filesystem::path& path);

/// Reads a PGM or PNG, chosen by the file's first bytes (not its name).
RasterImage read_raster_image(const std::filesystem::path& path);

}  // namespace floornav::io_detail
