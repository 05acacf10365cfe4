#include "utf8_input.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "floornav/core/input_error.hpp"
#include "floornav/core/utf8.hpp"

namespace floornav::io_detail {

void check_utf8_text(std::string_view text, const std::string& file) {
  const auto at = first_non_utf8(text);
  if (!at) return;
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(
                                   text.begin(), text.begin() + static_cast<long>(*at), '\n'));
  const std::size_t line_start = *at == 0 ? std::string_view::npos : text.rfind('\n', *at - 1);
  const std::size_t column = *at - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
  throw InputError(
      file, fmt::format("line {}, column {}", line, column),
      fmt::format("{}: {}; save the file as UTF-8", describe_non_utf8(text, *at), kWhyUtf8));
}

void check_utf8_value(std::string_view text, const std::string& file, const std::string& where) {
  const auto at = first_non_utf8(text);
  if (!at) return;
  throw InputError(
      file, where,
      fmt::format("{} (position {}): {}", describe_non_utf8(text, *at), *at + 1, kWhyUtf8));
}

void check_utf8_path(const std::filesystem::path& path, const std::string& file,
                     const std::string& where) {
  const std::string& text = path.native();
  const auto at = first_non_utf8(text);
  if (!at) return;
  throw InputError(file, where,
                   fmt::format("its path '{}': {}: {}; rename it", text,
                               describe_non_utf8(text, *at), kWhyUtf8));
}

}  // namespace floornav::io_detail
