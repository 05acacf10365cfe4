#include "floornav/io/ros_map.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "support/loader_test_support.hpp"

namespace floornav {
namespace {

namespace fs = std::filesystem;

/// A fresh folder per test (test::TempDirTest), plus map-file writers.
class RosMapTest : public test::TempDirTest {
 protected:
  /// A map yaml pointing at `image`, with the given extra/overriding lines.
  fs::path write_yaml(const std::string& name, const std::string& body) {
    return write(name, body);
  }

  /// Writes a PNG with libpng; `rows` holds height rows of packed samples.
  fs::path write_png(const std::string& name, png_uint_32 width, png_uint_32 height, int bit_depth,
                     int color_type, const std::vector<std::vector<png_byte>>& rows,
                     const std::vector<png_color>& palette = {},
                     const std::vector<png_byte>& transparency = {}) {
    const fs::path p = dir_ / name;
    std::FILE* f = std::fopen(p.string().c_str(), "wb");
    png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
    png_infop info = png_create_info_struct(png);
    png_init_io(png, f);
    png_set_IHDR(png, info, width, height, bit_depth, color_type, PNG_INTERLACE_NONE,
                 PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
    if (!palette.empty()) {
      png_set_PLTE(png, info, palette.data(), static_cast<int>(palette.size()));
    }
    if (!transparency.empty()) {
      png_color_16 gray_key{};  // for gray images: this gray value is transparent
      gray_key.gray = transparency.front();
      png_set_tRNS(png, info, transparency.data(), static_cast<int>(transparency.size()),
                   color_type == PNG_COLOR_TYPE_PALETTE ? nullptr : &gray_key);
    }
    png_write_info(png, info);
    for (const auto& row : rows) png_write_row(png, row.data());  // header-only when empty
    if (!rows.empty()) png_write_end(png, nullptr);
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    return p;
  }
};

using test::expect_input_error;

const std::string kYamlTail =
    "resolution: 0.5\norigin: [1.5, -2.0, 0.0]\nnegate: 0\noccupied_thresh: 0.65\n"
    "free_thresh: 0.196\n";

// Image (top row first):   0 254 205     p = 1.0 (occupied), 0.004 (free), 0.196 (unknown)
//                        255  50 205     p = 0.0 (free),     0.804 (occupied), unknown
std::string tiny_p5() {
  return std::string("P5\n# a comment\n3 2\n255\n") + std::string("\x00\xfe\xcd\xff\x32\xcd", 6);
}

TEST_F(RosMapTest, TinyPgmThresholdsAndFlip) {
  write("m.pgm", tiny_p5());
  const fs::path yaml = write_yaml("m.yaml", "image: m.pgm\n" + kYamlTail);
  const OccupancyGrid g = load_ros_map(yaml);
  ASSERT_EQ(g.width(), 3);
  ASSERT_EQ(g.height(), 2);
  EXPECT_EQ(g.resolution(), 0.5);
  EXPECT_EQ(g.origin().position, Vec2(1.5, -2.0));
  EXPECT_EQ(g.origin().theta, 0.0);
  // Grid row 0 is the image's bottom row.
  EXPECT_FALSE(g.occupied(0, 0));
  EXPECT_TRUE(g.occupied(1, 0));
  EXPECT_TRUE(g.occupied(2, 0));  // unknown -> occupied by default
  EXPECT_TRUE(g.occupied(0, 1));
  EXPECT_FALSE(g.occupied(1, 1));
  EXPECT_TRUE(g.occupied(2, 1));
  EXPECT_EQ(g.occupied_count(), 4u);

  const OccupancyGrid f = load_ros_map(yaml, RosMapOptions{.unknown = UnknownPolicy::Free});
  EXPECT_FALSE(f.occupied(2, 0));
  EXPECT_FALSE(f.occupied(2, 1));
  EXPECT_EQ(f.occupied_count(), 2u);
}

TEST_F(RosMapTest, UnknownCellsAreMarkedForPicturesUnderEitherPolicy) {
  write("m.pgm", tiny_p5());
  const fs::path yaml = write_yaml("m.yaml", "image: m.pgm\n" + kYamlTail);
  for (const UnknownPolicy policy : {UnknownPolicy::Occupied, UnknownPolicy::Free}) {
    const OccupancyGrid g = load_ros_map(yaml, RosMapOptions{.unknown = policy});
    ASSERT_TRUE(g.has_unknown());
    for (int iy = 0; iy < 2; ++iy)
      for (int ix = 0; ix < 3; ++ix) EXPECT_EQ(g.unknown(ix, iy), ix == 2) << ix << " " << iy;
  }
  // A map with no unknown pixel carries no layer.
  write("k.pgm", std::string("P5\n2 1\n255\n") + std::string("\x00\xfe", 2));
  EXPECT_FALSE(load_ros_map(write_yaml("k.yaml", "image: k.pgm\n" + kYamlTail)).has_unknown());
}

TEST_F(RosMapTest, Negate) {
  // Negated values 255 - v: top 255 1 50 -> p 0 (free), 0.996, 0.804 (occupied);
  // bottom 0 205 50 -> p 1 (occupied), 0.196 (unknown), 0.804 (occupied).
  write("m.pgm", tiny_p5());
  const fs::path yaml = write_yaml("m.yaml",
                                   "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: 1\n"
                                   "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  const OccupancyGrid g = load_ros_map(yaml, RosMapOptions{.unknown = UnknownPolicy::Free});
  EXPECT_TRUE(g.occupied(0, 0));
  EXPECT_FALSE(g.occupied(1, 0));
  EXPECT_TRUE(g.occupied(2, 0));
  EXPECT_FALSE(g.occupied(0, 1));
  EXPECT_TRUE(g.occupied(1, 1));
  EXPECT_TRUE(g.occupied(2, 1));
  // negate may also be a YAML bool.
  const fs::path yaml_bool =
      write_yaml("b.yaml",
                 "image: m.pgm\nresolution: 0.5\norigin: [0, 0, 0]\nnegate: true\n"
                 "occupied_thresh: 0.65\nfree_thresh: 0.196\n");
  EXPECT_EQ(load_ros_map(yaml_bool).occupied_count(), 5u);
}

TEST_F(RosMapTest, ThresholdsAreStrict) {
  // Pixel 204: p = 51 / 255 = 0.2 exactly, neither > 0.2 nor < 0.2: unknown.
  write("m.pgm", std::string("P5 1 1 255 ") + "\xcc");
  const fs::path yaml = write_yaml("m.yaml",
                                   "image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\n"
                                   "occupied_thresh: 0.2\nfree_thresh: 0.2\n");
  EXPECT_EQ(load_ros_map(yaml, {.unknown = UnknownPolicy::Free}).occupied_count(), 0u);
  EXPECT_EQ(load_ros_map(yaml, {.unknown = UnknownPolicy::Occupied}).occupied_count(), 1u);
}

TEST_F(RosMapTest, OriginYawAndAbsoluteImagePath) {
  const fs::path image = write("m.pgm", tiny_p5());
  const fs::path yaml = write_yaml(
      "sub.yaml", "image: " + image.string() +
                      "\nresolution: 0.1\norigin: [1, 2, 1.5707963267948966]\n"
                      "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
  const OccupancyGrid g = load_ros_map(yaml);
  EXPECT_DOUBLE_EQ(g.origin().theta, kPi / 2);
  EXPECT_EQ(g.origin().position, Vec2(1.0, 2.0));
}

TEST_F(RosMapTest, PlainPgmWithCommentsAndOtherMaxval) {
  // P2 with maxval 1000: 0 -> black (occupied), 1000 -> white (free), 500 -> 128 (unknown).
  write("m.pgm", "P2\n# comment\n2 2 # inline comment\n1000\n0 1000\n# between rows\n500 1000\n");
  const OccupancyGrid g = load_ros_image_map(dir_ / "m.pgm", 0.25);
  EXPECT_EQ(g.resolution(), 0.25);
  EXPECT_EQ(g.origin().position, Vec2(0.0, 0.0));
  EXPECT_TRUE(g.occupied(0, 1));  // image top-left
  EXPECT_FALSE(g.occupied(1, 1));
  EXPECT_TRUE(g.occupied(0, 0));  // unknown
  EXPECT_FALSE(g.occupied(1, 0));
  EXPECT_FALSE(
      load_ros_image_map(dir_ / "m.pgm", 0.25, {.unknown = UnknownPolicy::Free}).occupied(0, 0));
}

TEST_F(RosMapTest, SixteenBitPgm) {
  write("m.pgm", std::string("P5\n2 1\n65535\n") + std::string("\xff\xff\x00\x00", 4));
  const OccupancyGrid g = load_ros_image_map(dir_ / "m.pgm", 1.0);
  EXPECT_FALSE(g.occupied(0, 0));
  EXPECT_TRUE(g.occupied(1, 0));
}

TEST_F(RosMapTest, PngColourTypes) {
  // RGB: (0, 255, 0) averages to 85, p = 0.667 > 0.65: occupied. (A luminance-weighted gray,
  // 150, would be unknown, and free under UnknownPolicy::Free.)
  write_png("rgb.png", 2, 1, 8, PNG_COLOR_TYPE_RGB, {{0, 255, 0, 255, 255, 255}});
  const OccupancyGrid rgb =
      load_ros_image_map(dir_ / "rgb.png", 1.0, {.unknown = UnknownPolicy::Free});
  EXPECT_TRUE(rgb.occupied(0, 0));
  EXPECT_FALSE(rgb.occupied(1, 0));

  // RGBA: alpha is ignored (a transparent white pixel is still free).
  write_png("rgba.png", 2, 1, 8, PNG_COLOR_TYPE_RGB_ALPHA, {{255, 255, 255, 0, 0, 0, 0, 255}});
  const OccupancyGrid rgba = load_ros_image_map(dir_ / "rgba.png", 1.0);
  EXPECT_FALSE(rgba.occupied(0, 0));
  EXPECT_TRUE(rgba.occupied(1, 0));

  // Gray + alpha, 2 rows: flip.
  write_png("ga.png", 1, 2, 8, PNG_COLOR_TYPE_GRAY_ALPHA, {{0, 10}, {254, 255}});
  const OccupancyGrid ga = load_ros_image_map(dir_ / "ga.png", 1.0);
  EXPECT_TRUE(ga.occupied(0, 1));
  EXPECT_FALSE(ga.occupied(0, 0));

  // Palette: the colours count, not the indices.
  write_png("pal.png", 3, 1, 8, PNG_COLOR_TYPE_PALETTE, {{0, 1, 0}},
            {png_color{255, 255, 255}, png_color{0, 0, 0}});
  const OccupancyGrid pal = load_ros_image_map(dir_ / "pal.png", 1.0);
  EXPECT_FALSE(pal.occupied(0, 0));
  EXPECT_TRUE(pal.occupied(1, 0));
  EXPECT_FALSE(pal.occupied(2, 0));

  // Palette with a tRNS chunk (a transparent entry, as GIMP saves maps): transparency is dropped
  // like an alpha channel, the colours count.
  write_png("pal_trns.png", 3, 1, 8, PNG_COLOR_TYPE_PALETTE, {{0, 1, 0}},
            {png_color{255, 255, 255}, png_color{0, 0, 0}}, {0, 255});
  const OccupancyGrid pal_trns = load_ros_image_map(dir_ / "pal_trns.png", 1.0);
  EXPECT_FALSE(pal_trns.occupied(0, 0));
  EXPECT_TRUE(pal_trns.occupied(1, 0));
  EXPECT_FALSE(pal_trns.occupied(2, 0));
  // Gray with a tRNS key: likewise.
  write_png("gray_trns.png", 2, 1, 8, PNG_COLOR_TYPE_GRAY, {{255, 0}}, {}, {255});
  const OccupancyGrid gray_trns = load_ros_image_map(dir_ / "gray_trns.png", 1.0);
  EXPECT_FALSE(gray_trns.occupied(0, 0));
  EXPECT_TRUE(gray_trns.occupied(1, 0));

  // 16-bit gray (big-endian samples).
  write_png("g16.png", 2, 1, 16, PNG_COLOR_TYPE_GRAY, {{0xff, 0xff, 0x00, 0x00}});
  const OccupancyGrid g16 = load_ros_image_map(dir_ / "g16.png", 1.0);
  EXPECT_FALSE(g16.occupied(0, 0));
  EXPECT_TRUE(g16.occupied(1, 0));

  // 1-bit gray: 0b10000000 -> white, black.
  write_png("g1.png", 2, 1, 1, PNG_COLOR_TYPE_GRAY, {{0x80}});
  const OccupancyGrid g1 = load_ros_image_map(dir_ / "g1.png", 1.0);
  EXPECT_FALSE(g1.occupied(0, 0));
  EXPECT_TRUE(g1.occupied(1, 0));

  // Through a yaml too.
  const fs::path yaml = write_yaml("p.yaml", "image: rgb.png\n" + kYamlTail);
  EXPECT_EQ(load_ros_map(yaml).width(), 2);
}

TEST_F(RosMapTest, HugeImagesAreRefusedFromTheHeader) {
  // 100000 x 100000 = 10^10 cells, and no pixel data at all.
  write("huge.pgm", "P5\n100000 100000\n255\n");
  expect_input_error([&] { load_ros_image_map(dir_ / "huge.pgm", 0.05); }, "too large");
  write_png("huge.png", 100000, 100000, 8, PNG_COLOR_TYPE_GRAY, {});
  expect_input_error([&] { load_ros_image_map(dir_ / "huge.png", 0.05); }, "too large");
}

TEST_F(RosMapTest, BadImages) {
  write("short.pgm", std::string("P5\n3 2\n255\n") + std::string("\x00\x01\x02\x03", 4));
  expect_input_error([&] { load_ros_image_map(dir_ / "short.pgm", 1.0); },
                     "truncated image data: expected 6 bytes of pixels, got 4");
  write("short2.pgm", "P2\n2 2\n255\n0 1\n2\n");
  expect_input_error([&] { load_ros_image_map(dir_ / "short2.pgm", 1.0); }, "truncated");
  write("over.pgm", "P2\n1 1\n100\n101\n");
  expect_input_error([&] { load_ros_image_map(dir_ / "over.pgm", 1.0); }, "exceeds maxval 100");
  write("zero.pgm", "P5\n0 2\n255\n");
  expect_input_error([&] { load_ros_image_map(dir_ / "zero.pgm", 1.0); }, "empty");
  write("p6.ppm", "P6\n1 1\n255\nabc");
  expect_input_error([&] { load_ros_image_map(dir_ / "p6.ppm", 1.0); }, "unsupported image format");
  // A PNG cut in the middle of its data.
  write_png("full.png", 64, 64, 8, PNG_COLOR_TYPE_RGB,
            std::vector<std::vector<png_byte>>(64, std::vector<png_byte>(192, 7)));
  std::string bytes;
  {
    std::ifstream in(dir_ / "full.png", std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  write("cut.png", bytes.substr(0, bytes.size() / 2));
  // Either libpng's read error or its complaint about the missing data.
  expect_input_error([&] { load_ros_image_map(dir_ / "cut.png", 1.0); }, "cut.png: ");
  expect_input_error([&] { load_ros_image_map(dir_ / "missing.pgm", 1.0); }, "does not exist");
  write("m.pgm", tiny_p5());
  expect_input_error([&] { load_ros_image_map(dir_ / "m.pgm", 0.0); }, "resolution");
  expect_input_error([&] { load_ros_image_map(dir_ / "m.pgm", std::nan("")); }, "resolution");
}

TEST_F(RosMapTest, BadYaml) {
  write("m.pgm", tiny_p5());
  struct Case {
    std::string yaml;
    std::string needle;
  };
  const std::string keys =
      "origin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  const std::vector<Case> cases = {
      {"image: m.pgm\n" + keys, ":resolution: missing key 'resolution'"},
      {"resolution: 0.1\n" + keys, "missing key 'image'"},
      {"image: m.pgm\nresolution: -1\n" + keys, "line 2: resolution: must be positive"},
      {"image: m.pgm\nresolution: 0\n" + keys, "resolution: must be positive"},
      {"image: m.pgm\nresolution: .nan\n" + keys, "resolution: expected a finite number"},
      {"image: m.pgm\nresolution: nan\n" + keys, "resolution: expected a finite number"},
      {"image: m.pgm\nresolution: abc\n" + keys, "resolution: expected a finite number, got 'abc'"},
      {"image: m.pgm\nresolution: [1]\n" + keys, "resolution: expected a number, got a list"},
      {"image: [m.pgm]\nresolution: 1\n" + keys, "image: expected a string"},
      {"image: m.pgm\nresolution: 1\norigin: [0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
       "free_thresh: 0.196\n",
       "origin: expected a list [x, y, yaw]"},
      {"image: m.pgm\nresolution: 1\norigin: [0, x, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
       "free_thresh: 0.196\n",
       "origin: expected a finite number, got 'x'"},
      {"image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: maybe\noccupied_thresh: 0.65\n"
       "free_thresh: 0.196\n",
       "negate: expected 0, 1, true or false"},
      {"image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 1.5\n"
       "free_thresh: 0.196\n",
       "line 5: occupied_thresh: must be in [0, 1]"},
      {"image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n"
       "free_thresh: -0.1\n",
       "free_thresh: must be in [0, 1]"},
      {"image: m.pgm\nresolution: 1\norigin: [0, 0, 0]\nnegate: 0\noccupied_thresh: 0.65\n",
       "missing key 'free_thresh'"},
      {"image: m.pgm\nresolution: 1\n" + keys + "mode: fuzzy\n", "unknown mode 'fuzzy'"},
      {"image: other.pgm\nresolution: 1\n" + keys, "does not exist"},
      {"image: m.pgm\nresolution: 1\n  bad: [\n", "invalid YAML"},
      {"- just\n- a list\n", "expected a YAML map"},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const fs::path yaml = write_yaml("bad" + std::to_string(i) + ".yaml", cases[i].yaml);
    SCOPED_TRACE("case " + std::to_string(i));
    expect_input_error([&] { load_ros_map(yaml); }, cases[i].needle);
  }
  expect_input_error([&] { load_ros_map(dir_ / "none.yaml"); }, "does not exist");
  // The error carries the file and where.
  try {
    load_ros_map(write_yaml("w.yaml", "image: m.pgm\nresolution: -1\n" + keys));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file, (dir_ / "w.yaml").string());
    EXPECT_EQ(e.where, "line 2");
  }
}

// --- the real maps under data/maps -----------------------------------------------------------

fs::path data_maps() {
  return fs::path(FLOORNAV_MAPS_DIR);
}

/// The few small maps copied into the repository (tests/data/maps/SOURCES.md).
fs::path test_maps() {
  return fs::path(FLOORNAV_TEST_DATA_DIR) / "maps";
}

/// Counts of pixel values in a binary PGM, read independently of the loader (header without
/// comments after the first line).
struct PgmBytes {
  int width{0};
  int height{0};
  std::string raster;
};

PgmBytes read_pgm_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::string magic, line;
  std::getline(in, magic);
  while (in.peek() == '#') std::getline(in, line);
  PgmBytes out;
  int maxval = 0;
  in >> out.width >> out.height >> maxval;
  in.get();
  out.raster.resize(static_cast<std::size_t>(out.width) * out.height);
  in.read(out.raster.data(), static_cast<std::streamsize>(out.raster.size()));
  return out;
}

TEST(RosMapRealFiles, AwsWarehouse002) {
  const fs::path yaml = data_maps() / "aws-robomaker-small-warehouse/002/map.yaml";
  const OccupancyGrid g = load_ros_map(yaml, {.unknown = UnknownPolicy::Free});
  ASSERT_EQ(g.width(), 1536);
  ASSERT_EQ(g.height(), 1504);
  EXPECT_DOUBLE_EQ(g.resolution(), 0.02);
  EXPECT_DOUBLE_EQ(g.origin().position.x(), -10.0);
  EXPECT_DOUBLE_EQ(g.origin().position.y(), -20.24);
  // Every cell against the raw bytes: only 0 (black) is occupied when unknown (205) is free;
  // image row y is grid row height - 1 - y.
  const PgmBytes raw = read_pgm_bytes(data_maps() / "aws-robomaker-small-warehouse/002/map.pgm");
  ASSERT_EQ(raw.width, 1536);
  std::size_t mismatches = 0;
  for (int y = 0; y < raw.height; ++y) {
    for (int x = 0; x < raw.width; ++x) {
      const bool black = raw.raster[static_cast<std::size_t>(y) * raw.width + x] == '\0';
      if (g.occupied(x, raw.height - 1 - y) != black) ++mismatches;
    }
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(g.occupied_count(), 14173u);  // pixels of value 0
  // Unknown (205: p = 0.196 > free_thresh 0.196) is occupied by default.
  EXPECT_EQ(load_ros_map(yaml).occupied_count(), 14173u + 1710398u);
}

TEST(RosMapRealFiles, OtherYamlMaps) {
  // depot: free_thresh 0.25 > p(205), so its grey pixels load as free whatever the policy.
  const OccupancyGrid depot = load_ros_map(test_maps() / "nav2-bringup/depot.yaml");
  EXPECT_EQ(depot.width(), 604);
  EXPECT_EQ(depot.height(), 307);
  EXPECT_EQ(depot.occupied_count(), 5947u);
  // TurtleBot3 world: 795 black, 138722 unknown.
  const fs::path tb3 = test_maps() / "turtlebot3/map.yaml";
  EXPECT_EQ(load_ros_map(tb3).occupied_count(), 795u + 138722u);
  EXPECT_EQ(load_ros_map(tb3, {.unknown = UnknownPolicy::Free}).occupied_count(), 795u);
  // lse_arena: 0 and 255 plus one 239 (p = 0.063, free).
  const OccupancyGrid lse = load_ros_map(test_maps() / "ros-navigation-tutorials/lse_arena.yaml");
  EXPECT_EQ(lse.width(), 80);
  EXPECT_EQ(lse.height(), 60);
  EXPECT_EQ(lse.occupied_count(), 345u);
  // AWS 005: an 8-bit RGB PNG; counts from decoding the file separately (channel mean).
  const fs::path aws5 = test_maps() / "aws-robomaker-small-warehouse/005/map.yaml";
  const OccupancyGrid png = load_ros_map(aws5, {.unknown = UnknownPolicy::Free});
  EXPECT_EQ(png.width(), 286);
  EXPECT_EQ(png.height(), 423);
  EXPECT_DOUBLE_EQ(png.resolution(), 0.05);
  EXPECT_DOUBLE_EQ(png.origin().position.x(), -7.0);
  EXPECT_DOUBLE_EQ(png.origin().position.y(), -10.5);
  EXPECT_EQ(png.occupied_count(), 3673u);
  EXPECT_EQ(load_ros_map(aws5).occupied_count(), 3673u + 23607u);
}

TEST(RosMapRealFiles, WillowWithoutYaml) {
  const OccupancyGrid g =
      load_ros_image_map(data_maps() / "ros-navigation-tutorials/willow-full.pgm", 0.1);
  EXPECT_EQ(g.width(), 584);
  EXPECT_EQ(g.height(), 526);
  Vec2 lo, hi;
  g.world_extent(&lo, &hi);
  EXPECT_NEAR(hi.x(), 58.4, 1e-9);
  EXPECT_NEAR(hi.y(), 52.6, 1e-9);
  EXPECT_GT(g.occupied_count(), 0u);
  const OccupancyGrid fine =
      load_ros_image_map(data_maps() / "ros-navigation-tutorials/willow-full-0.05.pgm", 0.05);
  EXPECT_EQ(fine.width(), 1165);
  EXPECT_EQ(fine.height(), 945);
}

}  // namespace
}  // namespace floornav
