// PNG reading through libpng. libpng reports errors by longjmp, so every libpng call happens in
// one of two small functions whose frames hold only trivially destructible locals; they return
// false on error and the caller throws.

#include <png.h>

#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "floornav/core/input_error.hpp"
#include "io/input_file.hpp"
#include "io/maps/raster_image.hpp"

namespace floornav::io_detail {
namespace {

struct PngReader {
  std::FILE* file{nullptr};
  png_structp png{nullptr};
  png_infop info{nullptr};
  char message[256]{};

  PngReader() = default;
  PngReader(const PngReader&) = delete;
  PngReader& operator=(const PngReader&) = delete;
  ~PngReader() {
    if (png != nullptr) png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr);
    if (file != nullptr) std::fclose(file);
  }
};

extern "C" void on_png_error(png_structp png, png_const_charp msg) {
  auto* reader = static_cast<PngReader*>(png_get_error_ptr(png));
  std::snprintf(reader->message, sizeof reader->message, "%s", msg);
  png_longjmp(png, 1);
}

extern "C" void on_png_warning(png_structp, png_const_charp) {}  // e.g. "iCCP: known incorrect"

struct PngHeader {
  png_uint_32 width;
  png_uint_32 height;
  int channels;
  png_size_t row_bytes;
};

/// Reads the header and sets the transforms to 8-bit gray or RGB without alpha.
bool read_header(PngReader* r, PngHeader* h) {
  if (setjmp(png_jmpbuf(r->png))) return false;
  png_init_io(r->png, r->file);
  png_set_sig_bytes(r->png, 8);
  png_read_info(r->png, r->info);
  h->width = png_get_image_width(r->png, r->info);
  h->height = png_get_image_height(r->png, r->info);
  const int color_type = png_get_color_type(r->png, r->info);
  const int bit_depth = png_get_bit_depth(r->png, r->info);
  if (bit_depth == 16) png_set_strip_16(r->png);
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(r->png);
  if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(r->png);
  // A tRNS chunk (transparency of a palette entry or of one gray/RGB value) is expanded to an
  // alpha channel by the transforms above; like an alpha channel, it is dropped.
  const bool transparency = png_get_valid(r->png, r->info, PNG_INFO_tRNS) != 0;
  if (transparency) png_set_tRNS_to_alpha(r->png);
  if ((color_type & PNG_COLOR_MASK_ALPHA) != 0 || transparency) png_set_strip_alpha(r->png);
  png_set_interlace_handling(r->png);
  png_read_update_info(r->png, r->info);
  h->channels = png_get_channels(r->png, r->info);
  h->row_bytes = png_get_rowbytes(r->png, r->info);
  return true;
}

bool read_rows(PngReader* r, png_bytepp rows) {
  if (setjmp(png_jmpbuf(r->png))) return false;
  png_read_image(r->png, rows);
  return true;
}

void check_size(const std::string& file, std::uint64_t width, std::uint64_t height) {
  if (width == 0 || height == 0) throw InputError(file, "header", "empty image");
  if (const std::string problem = map_size_problem(width, height, "image", "pixels");
      !problem.empty())
    throw InputError(file, "header", problem);
}

}  // namespace

RasterImage read_png(const std::filesystem::path& path) {
  const std::string file = path.string();
  check_input_file(path, "PNG image", kMaxImageBytes);
  PngReader r;
  r.file = std::fopen(file.c_str(), "rb");
  if (r.file == nullptr) throw InputError(file, "", "cannot open the image file");
  unsigned char signature[8] = {};
  if (std::fread(signature, 1, 8, r.file) != 8 || png_sig_cmp(signature, 0, 8) != 0) {
    throw InputError(file, "", "not a PNG image (bad signature)");
  }
  // Check the size in IHDR ourselves first: libpng's png_read_info goes on past IHDR, so a
  // header-only file of 10^10 pixels must be refused before libpng sees it.
  unsigned char ihdr[16] = {};
  if (std::fread(ihdr, 1, 16, r.file) != 16 || std::memcmp(ihdr + 4, "IHDR", 4) != 0) {
    throw InputError(file, "header", "truncated or corrupt PNG: no IHDR chunk");
  }
  const auto be32 = [](const unsigned char* b) {
    return (std::uint64_t{b[0]} << 24) | (std::uint64_t{b[1]} << 16) | (std::uint64_t{b[2]} << 8) |
           std::uint64_t{b[3]};
  };
  check_size(file, be32(ihdr + 8), be32(ihdr + 12));
  if (std::fseek(r.file, 8, SEEK_SET) != 0) throw InputError(file, "", "cannot seek in the file");
  r.png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &r, on_png_error, on_png_warning);
  if (r.png == nullptr) throw InputError(file, "", "libpng could not start");
  r.info = png_create_info_struct(r.png);
  if (r.info == nullptr) throw InputError(file, "", "libpng could not start");

  PngHeader h{};
  if (!read_header(&r, &h)) {
    throw InputError(file, "header", std::string("bad PNG header: ") + r.message);
  }
  check_size(file, h.width, h.height);
  const std::uint64_t cells = std::uint64_t{h.width} * std::uint64_t{h.height};
  if ((h.channels != 1 && h.channels != 3) ||
      h.row_bytes != static_cast<png_size_t>(h.width) * static_cast<png_size_t>(h.channels)) {
    throw InputError(file, "header", "unsupported PNG layout after conversion to 8 bits");
  }

  // Refuse a header that promises more pixels than the file could hold before allocating for
  // them: deflate expands at most 1032:1, and 1-bit palette pixels grow 24-fold to 8-bit RGB.
  std::error_code ec;
  const std::uint64_t file_bytes = std::filesystem::file_size(path, ec);
  if (!ec && cells * static_cast<std::uint64_t>(h.channels) > 1032u * 24u * file_bytes) {
    throw InputError(file, "",
                     "truncated or corrupt image data: " + std::to_string(file_bytes) +
                         " bytes cannot hold " + std::to_string(h.width) + " x " +
                         std::to_string(h.height) + " pixels");
  }

  RasterImage image;
  image.width = static_cast<int>(h.width);
  image.height = static_cast<int>(h.height);
  image.channels = h.channels;
  image.samples.resize(static_cast<std::size_t>(cells) * static_cast<std::size_t>(h.channels));
  std::vector<png_bytep> rows(h.height);
  for (png_uint_32 y = 0; y < h.height; ++y) rows[y] = image.samples.data() + y * h.row_bytes;
  if (!read_rows(&r, rows.data())) {
    throw InputError(file, "", std::string("truncated or corrupt image data: ") + r.message);
  }
  return image;
}

RasterImage read_raster_image(const std::filesystem::path& path) {
  const std::string file = path.string();
  check_input_file(path, "map image", kMaxImageBytes);
  std::FILE* f = std::fopen(file.c_str(), "rb");
  if (f == nullptr) throw InputError(file, "", "cannot open the image file");
  unsigned char head[8] = {};
  const std::size_t n = std::fread(head, 1, 8, f);
  std::fclose(f);
  if (n >= 2 && head[0] == 'P' && (head[1] == '5' || head[1] == '2')) return read_pgm(path);
  if (n == 8 && png_sig_cmp(head, 0, 8) == 0) return read_png(path);
  throw InputError(file, "", "unsupported image format (expected a PGM (P5/P2) or PNG file)");
}

}  // namespace floornav::io_detail
