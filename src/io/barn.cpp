#include "floornav/io/barn.hpp"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <string>

#include "floornav/core/input_error.hpp"

namespace floornav {

std::vector<std::array<std::int64_t, 2>> load_npy_int_pairs(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(file, "", "cannot open for reading");
  char magic[8];
  if (!in.read(magic, 8) || std::memcmp(magic, "\x93NUMPY", 6) != 0)
    throw InputError(file, "", "not a NumPy .npy file");
  const int major = static_cast<unsigned char>(magic[6]);
  std::uint32_t header_len = 0;
  unsigned char len_bytes[4] = {0, 0, 0, 0};
  const int len_size = major == 1 ? 2 : 4;
  if (!in.read(reinterpret_cast<char*>(len_bytes), len_size))
    throw InputError(file, "", "truncated header");
  for (int i = len_size - 1; i >= 0; --i) header_len = (header_len << 8) | len_bytes[i];
  if (header_len > 65536) throw InputError(file, "", "header too long");
  std::string header(header_len, '\0');
  if (!in.read(header.data(), header_len)) throw InputError(file, "", "truncated header");
  if (header.find("'descr': '<i8'") == std::string::npos)
    throw InputError(file, "header", "expected dtype '<i8'");
  if (header.find("'fortran_order': False") == std::string::npos)
    throw InputError(file, "header", "expected C order");
  const auto shape_at = header.find("'shape': (");
  if (shape_at == std::string::npos) throw InputError(file, "header", "no shape");
  long long rows = 0, cols = 0;
  if (std::sscanf(header.c_str() + shape_at, "'shape': (%lld, %lld)", &rows, &cols) != 2 ||
      cols != 2 || rows < 0 || rows > 10000000)
    throw InputError(file, "header", "expected shape (n, 2)");
  std::vector<std::array<std::int64_t, 2>> out(static_cast<std::size_t>(rows));
  for (auto& row : out)
    for (auto& v : row) {
      unsigned char b[8];
      if (!in.read(reinterpret_cast<char*>(b), 8))
        throw InputError(file, "", fmt::format("truncated: expected {} rows", rows));
      std::uint64_t u = 0;
      for (int i = 7; i >= 0; --i) u = (u << 8) | b[i];
      v = static_cast<std::int64_t>(u);
    }
  return out;
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
