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

// The rows of `r`, each ending with `suffix` (",name" for a fleet, "" for one robot).
// With `full` given, it is called whenever `out` holds kPiece bytes or more (and empties it).
constexpr std::size_t kPiece = 1 << 20;  // bytes
void append_rows(fmt::memory_buffer& out, const RunResult& r, std::string_view suffix,
                 const std::function<void()>& full = {}) {
  std::vector<std::string> names;
  names.reserve(r.mode_names.size());
  for (const std::string& n : r.mode_names) names.push_back(csv_field(n));
  for (const TrajectorySample& s : r.trajectory) {
    auto it = std::back_inserter(out);
    it = fmt::format_to(it, "{},{},{},{},{},{},{},{},", s.t, s.x, s.y, s.theta, s.v, s.omega,
                        s.w_left, s.w_right);
    if (s.mode >= 0 && static_cast<std::size_t>(s.mode) < names.size())
      fmt::format_to(it, "{}{}\n", names[static_cast<std::size_t>(s.mode)], suffix);
    else
      fmt::format_to(it, "mode_{}{}\n", s.mode, suffix);
    if (full && out.size() >= kPiece) full();
  }
}

}  // namespace

std::string trajectory_to_csv(const RunResult& r) {
  fmt::memory_buffer out;
  out.reserve(64 + r.trajectory.size() * 128);
  fmt::format_to(std::back_inserter(out), "t,x,y,theta,v,omega,w_left,w_right,mode\n");
  append_rows(out, r, "");
  return fmt::to_string(out);
}

void trajectory_csv_pieces(const FleetResult& f,
                           const std::function<void(std::string_view)>& sink) {
  fmt::memory_buffer out;
  out.reserve(kPiece + 4096);
  const std::function<void()> flush = [&] {
    sink(std::string_view(out.data(), out.size()));
    out.clear();
  };
  fmt::format_to(std::back_inserter(out), "t,x,y,theta,v,omega,w_left,w_right,mode,robot\n");
  std::string suffix;
  for (const RunResult& r : f.robots) {
    suffix.assign(1, ',');
    suffix += csv_field(r.scenario);
    append_rows(out, r, suffix, flush);
  }
  if (out.size() > 0) flush();
}

std::string trajectory_to_csv(const FleetResult& f) {
  std::string text;
  trajectory_csv_pieces(f, [&](std::string_view piece) { text.append(piece); });
  return text;
}

}  // namespace floornav
