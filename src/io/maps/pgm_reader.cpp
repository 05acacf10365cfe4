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

struct PgmHeader {
  bool binary{true};  ///< P5 (else P2, plain text)
  std::uint64_t width{0}, height{0}, maxval{0};
  std::size_t count() const { return static_cast<std::size_t>(width * height); }
  std::size_t bytes_per_sample() const { return maxval < 256 ? 1 : 2; }
};

PgmHeader read_header(PgmTokenizer& tok, const std::string& file, bool binary) {
  PgmHeader h;
  h.binary = binary;
  h.width = tok.number("width");
  h.height = tok.number("height");
  h.maxval = tok.number("maxval");
  if (h.width == 0 || h.height == 0) {
    throw InputError(
        file, tok.where(),
        "image size " + std::to_string(h.width) + " x " + std::to_string(h.height) + " is empty");
  }
  if (const std::string problem = map_size_problem(h.width, h.height, "image", "pixels");
      !problem.empty())
    throw InputError(file, tok.where(), problem);
  if (h.maxval == 0 || h.maxval > 65535) {
    throw InputError(file, tok.where(),
                     "maxval must be in 1..65535, got " + std::to_string(h.maxval));
  }
  if (binary) tok.end_of_header();
  return h;
}

// Refuses a header that promises more pixels than the file holds before allocating for them:
// P5 stores bytes_per_sample bytes per pixel, P2 at least a digit and a separator.
void check_room_for_pixels(const std::filesystem::path& path, std::uint64_t here,
                           const PgmHeader& h, const PgmTokenizer& tok, const std::string& file) {
  std::error_code ec;
  const auto file_bytes = std::filesystem::file_size(path, ec);
  if (ec || file_bytes < here) return;
  const std::uint64_t left = file_bytes - here;
  const std::size_t count = h.count();
  if (h.binary && left < count * h.bytes_per_sample()) {
    throw InputError(file, "",
                     "truncated image data: expected " +
                         std::to_string(count * h.bytes_per_sample()) + " bytes of pixels, got " +
                         std::to_string(left));
  }
  if (!h.binary && left < 2 * count - 1) {
    throw InputError(file, tok.where(),
                     "truncated: " + std::to_string(count) + " pixel values need at least " +
                         std::to_string(2 * count - 1) + " bytes, the file has " +
                         std::to_string(left) + " after the header");
  }
}

std::uint8_t to_8bit(std::uint64_t v, std::uint64_t maxval) {
  return static_cast<std::uint8_t>(maxval == 255 ? v : (v * 255 + maxval / 2) / maxval);
}

[[noreturn]] void above_maxval(std::uint64_t v, std::uint64_t maxval, const std::string& file,
                               const std::string& where) {
  throw InputError(
      file, where,
      "pixel value " + std::to_string(v) + " exceeds maxval " + std::to_string(maxval));
}

void read_binary_raster(std::istream& in, std::uint64_t raster_start, const PgmHeader& h,
                        const std::string& file, std::vector<std::uint8_t>& samples) {
  const std::size_t bytes_per_sample = h.bytes_per_sample();
  std::string raster(h.count() * bytes_per_sample, '\0');
  in.read(raster.data(), static_cast<std::streamsize>(raster.size()));
  const auto got = static_cast<std::size_t>(in.gcount());
  if (got != raster.size()) {
    throw InputError(file, "",
                     "truncated image data: expected " + std::to_string(raster.size()) +
                         " bytes of pixels, got " + std::to_string(got));
  }
  for (std::size_t i = 0; i < h.count(); ++i) {
    std::uint64_t v = static_cast<unsigned char>(raster[i * bytes_per_sample]);
    if (bytes_per_sample == 2) v = (v << 8) | static_cast<unsigned char>(raster[i * 2 + 1]);
    if (v > h.maxval)
      above_maxval(v, h.maxval, file,
                   "byte " + std::to_string(raster_start + i * bytes_per_sample));
    samples[i] = to_8bit(v, h.maxval);
  }
}

void read_plain_raster(PgmTokenizer& tok, const PgmHeader& h, const std::string& file,
                       std::vector<std::uint8_t>& samples) {
  for (std::size_t i = 0; i < h.count(); ++i) {
    const std::uint64_t v = tok.number("pixel values");
    if (v > h.maxval) above_maxval(v, h.maxval, file, tok.where());
    samples[i] = to_8bit(v, h.maxval);
  }
}

// The raster is all of the file: anything after it (a second image, pixels of a wrong size in
// the header, a stray row) means the map is not what the header says. Whitespace (and, in a
// plain PGM, comments) may close the file.
void check_nothing_after(std::istream& in, PgmTokenizer& tok, const PgmHeader& h,
                         const std::string& file) {
  const std::string size = std::to_string(h.width) + " x " + std::to_string(h.height);
  if (h.binary) {
    const auto after = static_cast<std::uint64_t>(in.tellg());
    for (int c; (c = in.get()) != std::char_traits<char>::eof();)
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r')
        throw InputError(file, "",
                         "data after the raster (from byte " + std::to_string(after) +
                             "): the file holds more than the " + size +
                             " pixels its header gives");
  } else if (!tok.at_end()) {
    throw InputError(file, tok.where(), "more pixel values than the " + size + " the header gives");
  }
}

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
  PgmTokenizer tok(in, file);
  const PgmHeader h = read_header(tok, file, magic[1] == '5');
  const auto here = static_cast<std::uint64_t>(in.tellg());
  if (in) check_room_for_pixels(path, here, h, tok, file);

  RasterImage image;
  image.width = static_cast<int>(h.width);
  image.height = static_cast<int>(h.height);
  image.channels = 1;
  image.samples.resize(h.count());
  if (h.binary)
    read_binary_raster(in, here, h, file, image.samples);
  else
    read_plain_raster(tok, h, file, image.samples);
  check_nothing_after(in, tok, h, file);
  return image;
}

}  // namespace floornav::io_detail
