#pragma once
// Strict whole-string number parsing for the map readers (std::from_chars: no locale, no
// trailing garbage). Private to the io library.

#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

namespace floornav::io_detail {

/// The largest magnitude any number read from an input file may have (metres, radians, seconds,
/// gains alike). Larger values are typos, and their sums and squares would overflow to infinity
/// in the world's index and the clearance computations.
inline constexpr double kMaxInputMagnitude = 1e9;

/// `s` without leading and trailing spaces, tabs, CR and LF.
inline std::string_view trim(std::string_view s) {
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!s.empty() && space(s.front())) s.remove_prefix(1);
  while (!s.empty() && space(s.back())) s.remove_suffix(1);
  return s;
}

/// The finite number `s` spells in full (decimal or exponent form, an optional leading '+'),
/// or nullopt (also for nan, inf and magnitudes above kMaxInputMagnitude).
inline std::optional<double> parse_double(std::string_view s) {
  s = trim(s);
  if (s.size() > 1 && s.front() == '+' && s[1] != '-') s.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || ec != std::errc{} || end != s.data() + s.size() || !std::isfinite(value) ||
      std::abs(value) > kMaxInputMagnitude) {
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

/// When `s` spells a number that parse_double rejects only for its size, why: "'1e300' is too
/// large (more than 1e9 in magnitude)" or "'1e999' is out of the range of a double"; nullopt
/// otherwise (the caller says that `s` is not a finite number).
inline std::optional<std::string> magnitude_problem(std::string_view s) {
  s = trim(s);
  std::string out(1, '\'');
  out.append(s);
  out += "' is ";
  if (s.size() > 1 && s.front() == '+' && s[1] != '-') s.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (s.empty() || end != s.data() + s.size()) return std::nullopt;
  if (ec == std::errc::result_out_of_range) return out + "out of the range of a double";
  if (ec == std::errc{} && std::isfinite(value) && std::abs(value) > kMaxInputMagnitude)
    return out + "too large (more than 1e9 in magnitude)";
  return std::nullopt;
}

}  // namespace floornav::io_detail
