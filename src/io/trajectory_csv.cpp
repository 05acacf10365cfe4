#include "floornav/io/trajectory_csv.hpp"

#include <fmt/format.h>

#include <iterator>
#include <string_view>
#include <vector>

namespace floornav {

namespace {

/// A CSV field: quoted (with doubled quotes) only when it holds a separator, quote or newline.
std::string csv_field(std::string_view text) {
  if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += '"';
  return out;
}

}  // namespace

std::string trajectory_to_csv(const RunResult& r) {
  std::vector<std::string> names;
  names.reserve(r.mode_names.size());
  for (const std::string& n : r.mode_names) names.push_back(csv_field(n));

  fmt::memory_buffer out;
  out.reserve(64 + r.trajectory.size() * 128);
  auto it = std::back_inserter(out);
  fmt::format_to(it, "t,x,y,theta,v,omega,w_left,w_right,mode\n");
  for (const TrajectorySample& s : r.trajectory) {
    it = fmt::format_to(it, "{},{},{},{},{},{},{},{},", s.t, s.x, s.y, s.theta, s.v, s.omega,
                        s.w_left, s.w_right);
    if (s.mode >= 0 && static_cast<std::size_t>(s.mode) < names.size())
      it = fmt::format_to(it, "{}\n", names[static_cast<std::size_t>(s.mode)]);
    else
      it = fmt::format_to(it, "mode_{}\n", s.mode);
  }
  return fmt::to_string(out);
}

}  // namespace floornav
