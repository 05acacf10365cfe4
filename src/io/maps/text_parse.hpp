#pragma once
// Strict whole-string number parsing for the map readers (std::from_chars: no locale, no
// trailing garbage). Private to the io library.

#include <algorithm>
#include <charconv>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

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

/// `text` in single quotes for a message, cut to about `max` bytes (saying how long it was), so
/// that a message quoting a 5 MB line of input stays short. Never cuts a UTF-8 character.
inline std::string quote_input(std::string_view text, std::size_t max = 60) {
  std::size_t cut = std::min(max, text.size());
  while (cut < text.size() && cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80)
    --cut;
  std::string out(1, '\'');
  out.append(text.substr(0, cut));
  if (cut == text.size()) return out.append(1, '\'');
  out.append("...' (");
  out.append(std::to_string(text.size()));
  out.append(" bytes)");
  return out;
}

/// Levenshtein distance: how many single-character edits turn `a` into `b`.
inline std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

/// " (did you mean 'x'?)" for the candidate within 2 edits of `name`, or "".
inline std::string did_you_mean(std::string_view name,
                                std::span<const std::string_view> candidates) {
  std::string_view best;
  std::size_t best_distance = 3;
  for (std::string_view c : candidates) {
    const std::size_t d = edit_distance(name.substr(0, 64), c);
    if (d < best_distance) best_distance = d, best = c;
  }
  return best.empty() ? std::string() : " (did you mean '" + std::string(best) + "'?)";
}
inline std::string did_you_mean(std::string_view name,
                                std::initializer_list<std::string_view> candidates) {
  return did_you_mean(name,
                      std::span<const std::string_view>(candidates.begin(), candidates.size()));
}

}  // namespace floornav::io_detail
