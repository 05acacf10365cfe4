#pragma once
/// @file
/// Private to the render module: how numbers and text go into an SVG document. `Px` prints a
/// pixel coordinate with at most two decimals ("12.5", "-3"), never NaN or an exponent; `Xml`
/// escapes text for content and attributes. Every drawing function appends to an `SvgOut`.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string_view>

namespace floornav::render_detail {

/// A length or coordinate in pixels, printed with at most two decimals ("12.5", "-3", "0.07").
struct Px {
  double v;
};

/// Text to be placed in XML content or an attribute, escaped on output.
struct Xml {
  std::string_view text;
};

using SvgOut = std::back_insert_iterator<fmt::memory_buffer>;

inline constexpr const char* kFont = "Helvetica, Arial, sans-serif";

}  // namespace floornav::render_detail

template <>
struct fmt::formatter<floornav::render_detail::Px> {
  constexpr auto parse(format_parse_context& ctx) { return ctx.begin(); }
  template <class Context>
  auto format(const floornav::render_detail::Px& p, Context& ctx) const {
    const double v = std::isfinite(p.v) ? std::clamp(p.v, -1e9, 1e9) : 0.0;
    char text[48];
    const auto r = fmt::format_to_n(text, sizeof(text), "{:.2f}", v);
    std::size_t n = std::min(r.size, sizeof(text));
    while (n > 0 && text[n - 1] == '0') --n;
    if (n > 0 && text[n - 1] == '.') --n;
    std::string_view out(text, n);
    if (out == "-0" || out.empty()) out = "0";
    return std::copy(out.begin(), out.end(), ctx.out());
  }
};

template <>
struct fmt::formatter<floornav::render_detail::Xml> {
  constexpr auto parse(format_parse_context& ctx) { return ctx.begin(); }
  template <class Context>
  auto format(const floornav::render_detail::Xml& x, Context& ctx) const {
    auto out = ctx.out();
    for (char c : x.text) {
      switch (c) {
        case '&':
          out = fmt::format_to(out, "&amp;");
          break;
        case '<':
          out = fmt::format_to(out, "&lt;");
          break;
        case '>':
          out = fmt::format_to(out, "&gt;");
          break;
        case '"':
          out = fmt::format_to(out, "&quot;");
          break;
        case '\'':
          out = fmt::format_to(out, "&apos;");
          break;
        default:
          // Control characters other than tab and newline are not allowed in XML 1.0.
          if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') c = ' ';
          *out++ = c;
      }
    }
    return out;
  }
};
