#pragma once
// One CSV field (RFC 4180): quoted, with quotes doubled, when it holds a separator, a quote or a
// line break, so that no name (a robot's, a person's, a mode's) can end a field or a row early.
// Every text field of every CSV floornav writes goes through it. Private to the io library.

#include <string>
#include <string_view>

namespace floornav::io_detail {

inline std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace floornav::io_detail
