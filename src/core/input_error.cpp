#include "floornav/core/input_error.hpp"

#include <cstddef>

#include "floornav/core/utf8.hpp"

namespace floornav {
namespace {

/// `s` with control characters and bytes that are not UTF-8 spelled as escapes.
std::string one_line(const std::string& s) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const auto u = static_cast<unsigned char>(s[i]);
    if (u >= 0x80) {
      if (const std::size_t n = utf8_sequence_length(s, i); n > 0) {
        out.append(s, i, n);
        i += n;
        continue;
      }
    }
    if (u == '\n') {
      out += "\\n";
    } else if (u == '\r') {
      out += "\\r";
    } else if ((u < 0x20 && u != '\t') || u >= 0x7f) {
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 0xf];
    } else {
      out += static_cast<char>(u);
    }
    ++i;
  }
  return out;
}

/// `text` cut to at most kMaxMessageBytes: its head and tail, with how much was left out, so that
/// a message quoting a 5 MB line of input is still a line a terminal can show. Cuts fall on UTF-8
/// character boundaries (`text` has no control characters left: one_line ran first).
std::string capped(std::string text) {
  constexpr std::size_t kMaxMessageBytes = 480, kHead = 360, kTail = 100;
  if (text.size() <= kMaxMessageBytes) return text;
  const auto is_continuation = [&](std::size_t i) {
    return (static_cast<unsigned char>(text[i]) & 0xc0) == 0x80;
  };
  std::size_t head = kHead;
  while (head > 0 && is_continuation(head)) --head;
  std::size_t tail = text.size() - kTail;
  while (tail < text.size() && is_continuation(tail)) ++tail;
  return text.substr(0, head) + " [... " + std::to_string(tail - head) + " bytes cut ...] " +
         text.substr(tail);
}

}  // namespace

std::string InputError::render(const std::string& file, const std::string& where,
                               const std::string& what) {
  // "file:where: what"; a command-line value has no file: "--set sim.dt=-1: what".
  std::string out = file;
  if (!where.empty()) out += (out.empty() ? "" : ":") + where;
  return capped(one_line(out.empty() ? what : out + ": " + what));
}

}  // namespace floornav
