#include "utf8_input.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "floornav/core/input_error.hpp"
#include "floornav/core/utf8.hpp"

namespace floornav::io_detail {

namespace {

/// "byte 0xe9 is not UTF-8 (after 'caf')": the byte and a little of what comes before it.
std::string byte_problem(std::string_view text, std::size_t at) {
  const std::size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
  std::size_t from = line_start == std::string_view::npos || at == 0 ? 0 : line_start + 1;
  from = std::max(from, at > 24 ? at - 24 : std::size_t{0});
  const std::string_view before = text.substr(from, at - from);
  return fmt::format("byte 0x{:02x} is not UTF-8{}", static_cast<unsigned char>(text[at]),
                     before.empty() ? std::string() : fmt::format(" (after '{}')", before));
}

constexpr const char* kWhy =
    "floornav reads text as UTF-8 (names and paths are written to JSON, which holds nothing else)";

}  // namespace

void check_utf8_text(std::string_view text, const std::string& file) {
  const auto at = first_non_utf8(text);
  if (!at) return;
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(
                                   text.begin(), text.begin() + static_cast<long>(*at), '\n'));
  const std::size_t line_start = *at == 0 ? std::string_view::npos : text.rfind('\n', *at - 1);
  const std::size_t column = *at - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
  throw InputError(file, fmt::format("line {}, column {}", line, column),
                   fmt::format("{}: {}; save the file as UTF-8", byte_problem(text, *at), kWhy));
}

void check_utf8_value(std::string_view text, const std::string& file, const std::string& where) {
  const auto at = first_non_utf8(text);
  if (!at) return;
  throw InputError(file, where,
                   fmt::format("{} (position {}): {}", byte_problem(text, *at), *at + 1, kWhy));
}

void check_utf8_path(const std::filesystem::path& path, const std::string& file,
                     const std::string& where) {
  const std::string& text = path.native();
  const auto at = first_non_utf8(text);
  if (!at) return;
  throw InputError(
      file, where,
      fmt::format("the path '{}' holds {}: {}; rename it", text, byte_problem(text, *at), kWhy));
}

}  // namespace floornav::io_detail
