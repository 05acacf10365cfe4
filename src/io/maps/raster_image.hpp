#pragma once
// Reading the map images ROS map_server accepts (PGM and PNG) into 8-bit samples. Private to the
// io library.

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace floornav::io_detail {

/// Largest grid (in cells) a map may have: 2^26, an 8192 x 8192 map. A grid costs about 12 bytes
/// per cell once loaded (the occupancy, the distance transform, the free runs), so this bounds a
/// map at about 0.8 GB, whatever its file's size (a 55 kB 1-bit PNG can promise 2^28 pixels).
/// Larger headers are refused before any pixel is read.
inline constexpr std::uint64_t kMaxMapCells = std::uint64_t{1} << 26;

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
