// PGM (netpbm graymap) reading: P5 (binary) and P2 (plain), hand-written since the format is
// trivial: "P5" or "P2", then width, height and maxval as decimal numbers separated by
// whitespace, with '#' comments to the end of a line; for P5 exactly one whitespace byte, then
// the raster (1 byte per sample if maxval < 256, else 2 bytes big-endian); for P2 the samples as
// decimal numbers.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "floornav/core/input_error.hpp"
#include "io/input_file.hpp"
#include "io/maps/raster_image.hpp"

namespace floornav::io_detail {
namespace {

/// Reads the header and (for P2) the samples, keeping the line number for error messages.
class PgmTokenizer {
 public:
  PgmTokenizer(std::istream& in, std::string file) : in_(in), file_(std::move(file)) {}

  /// The next decimal number after whitespace and comments; `what` names it in errors.
  std::uint64_t number(const char* what) {
    skip_space_and_comments();
    int c = in_.peek();
    if (c == std::char_traits<char>::eof()) {
      throw InputError(file_, where(), std::string("truncated: the file ends before the ") + what);
    }
    if (c < '0' || c > '9') {
      throw InputError(file_, where(),
                       std::string("expected a decimal number for the ") + what + ", got '" +
                           static_cast<char>(c) + "'");
    }
    std::uint64_t value = 0;
    while (c >= '0' && c <= '9') {
      value = value * 10 + static_cast<std::uint64_t>(c - '0');
      if (value > (std::uint64_t{1} << 40)) {
        throw InputError(file_, where(), std::string("the ") + what + " is absurdly large");
      }
      in_.get();
      c = in_.peek();
    }
    return value;
  }

  /// Consumes the single whitespace byte that ends a P5 header.
  void end_of_header() {
    const int c = in_.get();
    if (c == std::char_traits<char>::eof()) {
      throw InputError(file_, where(), "truncated image data: file ends after the header");
    }
    if (c != ' ' && c != '\t' && c != '\n' && c != '\r' && c != '\v' && c != '\f') {
      throw InputError(file_, where(), "expected one whitespace byte after maxval");
    }
  }

  std::string where() const { return "line " + std::to_string(line_); }

  /// Whether only whitespace and comments are left.
  bool at_end() {
    skip_space_and_comments();
    return in_.peek() == std::char_traits<char>::eof();
  }

 private:
  void skip_space_and_comments() {
    for (;;) {
      const int c = in_.peek();
      if (c == '#') {
        while (in_.peek() != '\n' && in_.peek() != std::char_traits<char>::eof()) in_.get();
      } else if (c == '\n') {
        ++line_;
        in_.get();
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') {
        in_.get();
      } else {
        return;
      }
    }
  }

  std::istream& in_;
  std::string file_;
  int line_{1};
};

}  // namespace

RasterImage read_pgm(const std::filesystem::path& path) {
  const std::string file = path.string();
  check_input_file(path, "PGM image", kMaxImageBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open the image file");
  char magic[2] = {0, 0};
  in.read(magic, 2);
  if (in.gcount() != 2 || magic[0] != 'P' || (magic[1] != '5' && magic[1] != '2')) {
    throw InputError(file, "line 1", "not a PGM image (expected magic 'P5' or 'P2')");
  }
  const bool binary = magic[1] == '5';
  PgmTokenizer tok(in, file);
  const std::uint64_t width = tok.number("width");
  const std::uint64_t height = tok.number("height");
  const std::uint64_t maxval = tok.number("maxval");
  if (width == 0 || height == 0) {
    throw InputError(
        file, tok.where(),
        "image size " + std::to_string(width) + " x " + std::to_string(height) + " is empty");
  }
  if (const std::string problem = map_size_problem(width, height, "image", "pixels");
      !problem.empty())
    throw InputError(file, tok.where(), problem);
  if (maxval == 0 || maxval > 65535) {
    throw InputError(file, tok.where(),
                     "maxval must be in 1..65535, got " + std::to_string(maxval));
  }

  const std::size_t count = static_cast<std::size_t>(width * height);
  const std::size_t bytes_per_sample = maxval < 256 ? 1 : 2;
  if (binary) tok.end_of_header();
  // Refuse a header that promises more pixels than the file holds before allocating for them:
  // P5 stores bytes_per_sample bytes per pixel, P2 at least a digit and a separator.
  std::error_code ec;
  const auto file_bytes = std::filesystem::file_size(path, ec);
  const auto here = static_cast<std::uint64_t>(in.tellg());
  if (!ec && in && file_bytes >= here) {
    const std::uint64_t left = file_bytes - here;
    if (binary && left < count * bytes_per_sample) {
      throw InputError(file, "",
                       "truncated image data: expected " +
                           std::to_string(count * bytes_per_sample) + " bytes of pixels, got " +
                           std::to_string(left));
    }
    if (!binary && left < 2 * count - 1) {
      throw InputError(file, tok.where(),
                       "truncated: " + std::to_string(count) + " pixel values need at least " +
                           std::to_string(2 * count - 1) + " bytes, the file has " +
                           std::to_string(left) + " after the header");
    }
  }

  RasterImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.channels = 1;
  image.samples.resize(count);
  auto to_8bit = [maxval](std::uint64_t v) {
    return static_cast<std::uint8_t>(maxval == 255 ? v : (v * 255 + maxval / 2) / maxval);
  };
  auto check_max = [&](std::uint64_t v, const std::string& where) {
    if (v > maxval) {
      throw InputError(
          file, where,
          "pixel value " + std::to_string(v) + " exceeds maxval " + std::to_string(maxval));
    }
  };

  if (binary) {
    const auto raster_start = here;
    std::string raster(count * bytes_per_sample, '\0');
    in.read(raster.data(), static_cast<std::streamsize>(raster.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    if (got != raster.size()) {
      throw InputError(file, "",
                       "truncated image data: expected " + std::to_string(raster.size()) +
                           " bytes of pixels, got " + std::to_string(got));
    }
    for (std::size_t i = 0; i < count; ++i) {
      std::uint64_t v = static_cast<unsigned char>(raster[i * bytes_per_sample]);
      if (bytes_per_sample == 2) {
        v = (v << 8) | static_cast<unsigned char>(raster[i * 2 + 1]);
      }
      if (v > maxval) check_max(v, "byte " + std::to_string(raster_start + i * bytes_per_sample));
      image.samples[i] = to_8bit(v);
    }
  } else {
    for (std::size_t i = 0; i < count; ++i) {
      const std::uint64_t v = tok.number("pixel values");
      check_max(v, tok.where());
      image.samples[i] = to_8bit(v);
    }
  }
  // The raster is all of the file: anything after it (a second image, pixels of a wrong size in
  // the header, a stray row) means the map is not what the header says. Whitespace (and, in a
  // plain PGM, comments) may close the file.
  if (binary) {
    const auto after = static_cast<std::uint64_t>(in.tellg());
    for (int c; (c = in.get()) != std::char_traits<char>::eof();)
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r')
        throw InputError(file, "",
                         "data after the raster (from byte " + std::to_string(after) +
                             "): the file holds more than the " + std::to_string(width) + " x " +
                             std::to_string(height) + " pixels its header gives");
  } else if (!tok.at_end()) {
    throw InputError(file, tok.where(),
                     "more pixel values than the " + std::to_string(width) + " x " +
                         std::to_string(height) + " the header gives");
  }
  return image;
}

}  // namespace floornav::io_detail
