#pragma once
// Strict whole-string number parsing for the map readers (std::from_chars: no locale, no
// trailing garbage). Private to the io library.

#include <charconv>
#include <cmath>
#include <optional>
#include <string_view>

namespace floornav::io_detail {

/// `s` without leading and trailing spaces, tabs, CR and LF.
inline std::string_view trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

/// The finite number `s` spells in full (decimal or exponent form, an optional leading '+'),
/// or nullopt (also for nan and inf).
inline std::optional<double> parse_double(std::string_view s) {
  s = trim(s);
  if (s.size() > 1 && s.front() == '+' && s[1] != '-') s.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

/// The integer `s` spells in full (an optional leading '+' or '-'), or nullopt.
inline std::optional<long long> parse_int(std::string_view s) {
  s = trim(s);
  if (s.size() > 1 && s.front() == '+' && s[1] != '-') s.remove_prefix(1);
  long long value = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc{} || end != s.data() + s.size()) return std::nullopt;
  return value;
}

}  // namespace floornav::io_detail
