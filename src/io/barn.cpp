#include "floornav/io/barn.hpp"

#include <fmt/format.h>

#include <string>
#include <string_view>

#include "floornav/core/input_error.hpp"
#include "input_file.hpp"
#include "maps/text_parse.hpp"

namespace floornav {

namespace {

/// The header of a .npy file is a Python dict literal,
/// "{'descr': '<i8', 'fortran_order': False, 'shape': (32, 2), }" padded with spaces to a newline.
/// Read strictly: exactly these three keys, once each, and nothing else (a key inside a string
/// value or a third dimension must not pass for the real thing).
struct NpyHeader {
  std::string descr;
  bool fortran_order{true};
  std::vector<long long> shape;
};

class NpyHeaderParser {
 public:
  NpyHeaderParser(std::string_view text, std::string file) : s_(text), file_(std::move(file)) {}

  NpyHeader parse() {
    NpyHeader h;
    bool seen[3] = {false, false, false};
    expect('{');
    while (skip_space(), peek() != '}') {
      const std::string key = string_literal();
      expect(':');
      int k = -1;
      if (key == "descr") {
        k = 0;
        h.descr = string_literal();
      } else if (key == "fortran_order") {
        k = 1;
        h.fortran_order = boolean();
      } else if (key == "shape") {
        k = 2;
        h.shape = tuple();
      } else {
        bad("unknown key " + io_detail::quote_input(key) +
            " in the header (a .npy header has descr, fortran_order and shape)");
      }
      if (seen[k]) bad("the header gives " + io_detail::quote_input(key) + " twice");
      seen[k] = true;
      skip_space();
      if (peek() == ',') ++pos_;
    }
    ++pos_;
    for (; pos_ < s_.size(); ++pos_)
      if (s_[pos_] != ' ' && s_[pos_] != '\n') bad("text after the header's closing brace");
    if (!seen[0] || !seen[1] || !seen[2]) bad("the header lacks descr, fortran_order or shape");
    return h;
  }

 private:
  [[noreturn]] void bad(const std::string& what) const { throw InputError(file_, "header", what); }
  char peek() const { return pos_ < s_.size() ? s_[pos_] : '\0'; }
  void skip_space() {
    while (pos_ < s_.size() && s_[pos_] == ' ') ++pos_;
  }
  void expect(char c) {
    skip_space();
    if (peek() != c) bad(std::string("malformed header: expected '") + c + "'");
    ++pos_;
  }
  std::string string_literal() {
    skip_space();
    const char quote = peek();
    if (quote != '\'' && quote != '"') bad("malformed header: expected a quoted name");
    const auto end = s_.find(quote, pos_ + 1);
    if (end == std::string_view::npos) bad("malformed header: a string is not closed");
    std::string out(s_.substr(pos_ + 1, end - pos_ - 1));
    pos_ = end + 1;
    return out;
  }
  bool boolean() {
    skip_space();
    if (s_.substr(pos_, 4) == "True") return pos_ += 4, true;
    if (s_.substr(pos_, 5) == "False") return pos_ += 5, false;
    bad("malformed header: fortran_order is True or False");
  }
  std::vector<long long> tuple() {
    expect('(');
    std::vector<long long> out;
    while (skip_space(), peek() != ')') {
      std::size_t end = pos_;
      while (end < s_.size() && s_[end] >= '0' && s_[end] <= '9') ++end;
      const auto v = io_detail::parse_int(s_.substr(pos_, end - pos_));
      if (!v || end - pos_ > 12) bad("malformed header: a shape is a tuple of whole numbers");
      out.push_back(*v);
      pos_ = end;
      skip_space();
      if (peek() == ',') ++pos_;
      if (out.size() > 8) bad("malformed header: too many dimensions");
    }
    ++pos_;
    return out;
  }

  std::string_view s_;
  std::string file_;
  std::size_t pos_{0};
};

}  // namespace

std::vector<std::array<std::int64_t, 2>> load_npy_int_pairs(const std::filesystem::path& path) {
  const std::string file = path.string();
  const std::string bytes = io_detail::read_input_file(path, "NumPy .npy", io_detail::kMaxNpyBytes);
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0)
    throw InputError(file, "", "not a NumPy .npy file");
  const int major = static_cast<unsigned char>(bytes[6]);
  if (major < 1 || major > 3)
    throw InputError(file, "", fmt::format("unknown .npy format version {}", major));
  const std::size_t len_size = major == 1 ? 2 : 4;
  if (bytes.size() < 8 + len_size) throw InputError(file, "", "truncated header");
  std::size_t header_len = 0;
  for (std::size_t i = len_size; i-- > 0;)
    header_len = (header_len << 8) | static_cast<unsigned char>(bytes[8 + i]);
  const std::size_t data_start = 8 + len_size + header_len;
  if (header_len > 65536 || data_start > bytes.size())
    throw InputError(file, "", "truncated header");
  const NpyHeader h =
      NpyHeaderParser(std::string_view(bytes).substr(8 + len_size, header_len), file).parse();
  if (h.descr != "<i8")
    throw InputError(
        file, "header",
        "expected dtype '<i8' (little-endian int64), got " + io_detail::quote_input(h.descr));
  if (h.fortran_order) throw InputError(file, "header", "expected C order (fortran_order: False)");
  if (h.shape.size() != 2 || h.shape[1] != 2)
    throw InputError(
        file, "header",
        fmt::format("expected shape (n, 2), got a {}-dimensional array", h.shape.size()) +
            (h.shape.size() == 2 ? fmt::format(" of {} columns", h.shape[1]) : ""));
  const auto rows = static_cast<std::size_t>(h.shape[0]);
  const std::size_t data_bytes = bytes.size() - data_start;
  if (data_bytes != rows * 16)
    throw InputError(
        file, "",
        fmt::format("{} bytes of data, but shape ({}, 2) needs {}", data_bytes, rows, rows * 16));
  std::vector<std::array<std::int64_t, 2>> out(rows);
  const char* p = bytes.data() + data_start;
  for (auto& row : out)
    for (auto& v : row) {
      std::uint64_t u = 0;
      for (int i = 7; i >= 0; --i) u = (u << 8) | static_cast<unsigned char>(p[i]);
      v = static_cast<std::int64_t>(u);
      p += 8;
    }
  return out;
}

std::vector<std::array<std::int64_t, 2>> load_barn_path(const std::filesystem::path& path) {
  auto cells = load_npy_int_pairs(path);
  if (cells.empty()) throw InputError(path.string(), "", "an empty path (no cells)");
  for (std::size_t i = 0; i < cells.size(); ++i)
    for (const std::int64_t v : cells[i])
      if (v < 0 || v >= kBarnGridSize)
        throw InputError(path.string(), fmt::format("row {}", i),
                         fmt::format("cell ({}, {}) is outside BARN's {} x {} grid", cells[i][0],
                                     cells[i][1], kBarnGridSize, kBarnGridSize));
  return cells;
}

Vec2 barn_cell_to_world(std::int64_t row, std::int64_t col) {
  constexpr double kRadius = 0.075;  // the cylinders' radius; cells are 2 radii wide
  return {static_cast<double>(row) * 2.0 * kRadius - kRadius - 30.0 * 2.0 * kRadius,
          static_cast<double>(col) * 2.0 * kRadius + kRadius + 5.0};
}

double barn_optimal_time(const std::vector<std::array<std::int64_t, 2>>& path, const Vec2& start,
                         const Vec2& goal) {
  constexpr double kReferenceSpeed = 2.0;  // m/s, the challenge's
  double length = 0.0;
  Vec2 previous = start;
  for (const auto& cell : path) {
    const Vec2 p = barn_cell_to_world(cell[0], cell[1]);
    length += (p - previous).norm();
    previous = p;
  }
  length += (goal - previous).norm();
  return length / kReferenceSpeed;
}

}  // namespace floornav
