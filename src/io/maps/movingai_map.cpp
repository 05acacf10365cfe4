#include "floornav/io/movingai_map.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "floornav/core/input_error.hpp"
#include "io/input_file.hpp"
#include "io/maps/raster_image.hpp"
#include "io/maps/text_parse.hpp"
#include "io/utf8_input.hpp"

namespace floornav {
namespace {

/// Line-by-line reading that strips a trailing CR and counts lines from 1.
class LineReader {
 public:
  /// Checks first that `path` is a file of at most `max_bytes` (never a FIFO or a device).
  LineReader(const std::filesystem::path& path, const char* what, std::uint64_t max_bytes)
      : file_(path.string()) {
    io_detail::check_input_file(path, what, max_bytes);
    in_.open(path, std::ios::binary);
    if (!in_) throw InputError(file_, "", std::string("cannot open the ") + what + " file");
  }

  bool next(std::string& line) {
    if (!std::getline(in_, line)) return false;
    ++line_no_;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }

  std::string where() const { return "line " + std::to_string(line_no_); }
  const std::string& file() const { return file_; }
  [[noreturn]] void fail(const std::string& what) const { throw InputError(file_, where(), what); }

 private:
  std::ifstream in_;
  std::string file_;
  int line_no_{0};

 public:
  int line() const { return line_no_; }
};

/// Splits "word value" into its two space-separated parts.
bool split_pair(std::string_view line, std::string_view& word, std::string_view& value) {
  line = io_detail::trim(line);
  const auto space = line.find_first_of(" \t");
  if (space == std::string_view::npos) return false;
  word = line.substr(0, space);
  value = io_detail::trim(line.substr(space));
  return true;
}

/// MovingAI's terrain: '.' and 'G' ground, 'S' swamp (passable); '@' and 'O' out of bounds,
/// 'T' trees, 'W' water (not passable by a ground robot). Anything else is not a map character.
enum class Terrain { Free, Blocked, Unknown };
Terrain terrain(char c) {
  switch (c) {
    case '.':
    case 'G':
    case 'S':
      return Terrain::Free;
    case '@':
    case 'O':
    case 'T':
    case 'W':
      return Terrain::Blocked;
    default:
      return Terrain::Unknown;
  }
}

}  // namespace

OccupancyGrid load_movingai_map(const std::filesystem::path& map, double cell_size) {
  if (!(cell_size > 0.0) || !std::isfinite(cell_size)) {
    throw InputError(map.string(), "cell_size",
                     fmt::format("must be a positive finite number, got {:.6g}", cell_size));
  }
  LineReader in(map, "MovingAI map", io_detail::kMaxMovingAiMapBytes);
  std::string line;
  if (!in.next(line)) in.fail("empty file: expected 'type octile'");
  std::string_view word, value;
  if (!split_pair(line, word, value) || word != "type") in.fail("expected 'type octile'");
  if (value != "octile")
    in.fail("unsupported map type " + io_detail::quote_input(value) + " (expected octile)");

  long long width = -1;
  long long height = -1;
  for (int k = 0; k < 2; ++k) {
    if (!in.next(line)) in.fail("file ends in the header: expected 'height H' and 'width W'");
    if (!split_pair(line, word, value) || (word != "height" && word != "width")) {
      in.fail("expected 'height H' or 'width W', got " + io_detail::quote_input(line));
    }
    const auto n = io_detail::parse_int(value);
    if (!n || *n <= 0)
      in.fail(std::string(word) + " must be a positive integer, got " +
              io_detail::quote_input(value));
    long long& slot = word == "height" ? height : width;
    if (slot >= 0) in.fail("'" + std::string(word) + "' given twice");
    slot = *n;
  }
  // Each side alone first: the product of two sides near 2^32 would wrap around.
  const auto w64 = static_cast<std::uint64_t>(width);
  const auto h64 = static_cast<std::uint64_t>(height);
  if (const std::string problem = io_detail::map_size_problem(w64, h64, "map", "cells");
      !problem.empty())
    in.fail(problem);
  if (!in.next(line) || io_detail::trim(line) != "map") in.fail("expected 'map'");
  // Refuse a header that promises more cells than the file holds before allocating for them.
  std::error_code ec;
  const std::uint64_t file_bytes = std::filesystem::file_size(map, ec);
  if (!ec && file_bytes < w64 * h64) {
    in.fail("file ends before its " + std::to_string(height) + " map rows of " +
            std::to_string(width) + " cells (" + std::to_string(file_bytes) + " bytes in all)");
  }

  const int w = static_cast<int>(width);
  const int h = static_cast<int>(height);
  std::vector<std::uint8_t> occ(static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    if (!in.next(line)) {
      in.fail("file ends after " + std::to_string(y) + " of " + std::to_string(h) + " map rows");
    }
    if (line.size() != static_cast<std::size_t>(w)) {
      in.fail("map row " + std::to_string(y) + " has " + std::to_string(line.size()) +
              " characters, expected width " + std::to_string(w));
    }
    std::uint8_t* row = occ.data() + static_cast<std::size_t>(h - 1 - y) * w;
    for (int x = 0; x < w; ++x) {
      const Terrain t = terrain(line[x]);
      if (t == Terrain::Unknown) {
        const auto c = static_cast<unsigned char>(line[x]);
        in.fail(
            fmt::format("map row {}, column {}: {} is not a MovingAI terrain character "
                        "(. G S free; @ O T W blocked)",
                        y, x,
                        c >= 0x20 && c < 0x7f ? fmt::format("'{}'", line[x])
                                              : fmt::format("byte 0x{:02x}", c)));
      }
      row[x] = t == Terrain::Free ? 0 : 1;
    }
  }
  while (in.next(line)) {
    if (!io_detail::trim(line).empty()) {
      in.fail("more map rows than the height " + std::to_string(h));
    }
  }
  return OccupancyGrid(w, h, cell_size, Pose2{}, std::move(occ));
}

std::vector<MovingAiCase> load_movingai_scen(const std::filesystem::path& scen) {
  LineReader in(scen, "MovingAI scenario", io_detail::kMaxScenBytes);
  std::string line;
  if (!in.next(line)) in.fail("empty file: expected 'version 1'");
  {
    std::string_view word, value;
    if (!split_pair(line, word, value) || word != "version" || (value != "1" && value != "1.0")) {
      in.fail("expected 'version 1' or 'version 1.0', got " + io_detail::quote_input(line));
    }
  }
  static constexpr const char* kFields[9] = {"bucket",     "map",     "map width",
                                             "map height", "start x", "start y",
                                             "goal x",     "goal y",  "optimal length"};
  std::vector<MovingAiCase> cases;
  while (in.next(line)) {
    if (io_detail::trim(line).empty()) continue;
    // The map's name reaches the outputs (JSON): text, so UTF-8.
    io_detail::check_utf8_value(line, in.file(), in.where());
    std::vector<std::string_view> f;
    std::string_view rest(line);
    for (;;) {
      const auto tab = rest.find('\t');
      f.push_back(rest.substr(0, tab));
      if (tab == std::string_view::npos) break;
      rest.remove_prefix(tab + 1);
    }
    if (cases.size() >= kMaxScenRows)
      in.fail(fmt::format("more than {} rows: a .scen file holds at most that many cases",
                          kMaxScenRows));
    if (f.size() != 9) {
      in.fail("expected 9 tab-separated fields, got " + std::to_string(f.size()));
    }
    auto integer = [&](int k, long long lo, long long hi) {
      const auto v = io_detail::parse_int(f[k]);
      if (!v || *v < lo || *v > hi) {
        in.fail(std::string(kFields[k]) + " must be an integer in [" + std::to_string(lo) + ", " +
                std::to_string(hi) + "], got " + io_detail::quote_input(f[k]));
      }
      return static_cast<int>(*v);
    };
    MovingAiCase c;
    c.line = in.line();
    c.bucket = integer(0, 0, 1 << 30);
    c.map_file = std::string(io_detail::trim(f[1]));
    if (c.map_file.empty()) in.fail("map file name is empty");
    c.width = integer(2, 1, 1 << 30);
    c.height = integer(3, 1, 1 << 30);
    c.start_x = integer(4, 0, c.width - 1);
    c.start_y = integer(5, 0, c.height - 1);
    c.goal_x = integer(6, 0, c.width - 1);
    c.goal_y = integer(7, 0, c.height - 1);
    const auto length = io_detail::parse_double(f[8]);
    if (!length || *length < 0.0) {
      std::string what = "optimal length must be a non-negative number, got ";
      if (const auto size = io_detail::magnitude_problem(f[8])) {
        what += *size;
      } else {
        what += io_detail::quote_input(f[8]);
      }
      in.fail(what);
    }
    // An optimum below the straight line between the cell centres (or 0 between two cells) is not
    // a path length: path efficiencies against it would be meaningless. 1e-6 allows the rounding
    // of the 8 decimals MovingAI prints.
    const double straight = std::hypot(c.goal_x - c.start_x, c.goal_y - c.start_y);
    if (*length < straight * (1.0 - 1e-6) || (straight > 0.0 && !(*length > 0.0)))
      in.fail(
          fmt::format("optimal length {} is shorter than the straight line from the start to "
                      "the goal ({:.8g} cells): not the length of a path between them",
                      io_detail::quote_input(f[8]), straight));
    c.optimal_length = *length;
    cases.push_back(std::move(c));
  }
  return cases;
}

}  // namespace floornav
