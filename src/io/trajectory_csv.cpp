#include "floornav/io/trajectory_csv.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <string_view>
#include <vector>

#include "csv_field.hpp"

namespace floornav {

namespace {

using io_detail::csv_field;

constexpr std::size_t kPiece = 1 << 20;  // bytes handed to a sink at a time

/// The columns of a file: the trajectory's own, the robot's name (fleets), then the extras.
void append_header(fmt::memory_buffer& out, bool fleet, const std::vector<std::string>& extras) {
  auto it = std::back_inserter(out);
  it = fmt::format_to(it, "t,x,y,theta,v,omega,w_left,w_right,mode{}", fleet ? ",robot" : "");
  for (const std::string& c : extras) it = fmt::format_to(it, ",{}", csv_field(c));
  fmt::format_to(it, "\n");
}

// The rows of `r`: its samples, `suffix` (",name" for a fleet, "" for one robot), its extra
// values (NaN as an empty field) padded with empty fields to `extra_width` columns. Whenever
// `out` holds kPiece bytes or more, `full` is called (and empties it).
void append_rows(fmt::memory_buffer& out, const RunResult& r, std::string_view suffix,
                 std::size_t extra_width, const std::function<void()>& full) {
  std::vector<std::string> names;
  names.reserve(r.mode_names.size());
  for (const std::string& n : r.mode_names) names.push_back(csv_field(n));
  const std::size_t width = r.extra_columns.size();
  const bool extras = width > 0 && r.extra.size() == width * r.trajectory.size();
  for (std::size_t row = 0; row < r.trajectory.size(); ++row) {
    const TrajectorySample& s = r.trajectory[row];
    auto it = std::back_inserter(out);
    it = fmt::format_to(it, "{},{},{},{},{},{},{},{},", s.t, s.x, s.y, s.theta, s.v, s.omega,
                        s.w_left, s.w_right);
    if (s.mode >= 0 && static_cast<std::size_t>(s.mode) < names.size())
      it = fmt::format_to(it, "{}{}", names[static_cast<std::size_t>(s.mode)], suffix);
    else
      it = fmt::format_to(it, "mode_{}{}", s.mode, suffix);
    for (std::size_t c = 0; c < extra_width; ++c) {
      const double v = extras && c < width ? r.extra[row * width + c] : std::nan("");
      it = std::isfinite(v) ? fmt::format_to(it, ",{}", v) : fmt::format_to(it, ",");
    }
    fmt::format_to(it, "\n");
    if (out.size() >= kPiece) full();
  }
}

/// The extra columns of a fleet's file: the longest list of any robot (they differ only in how
/// many range_i columns there are).
std::vector<std::string> fleet_extras(const FleetResult& f) {
  std::vector<std::string> out;
  for (const RunResult& r : f.robots)
    if (r.extra_columns.size() > out.size()) out = r.extra_columns;
  return out;
}

/// Hands `text` to `sink` in pieces; returns the whole when `sink` is empty.
class Pieces {
 public:
  explicit Pieces(const std::function<void(std::string_view)>* sink) : sink_(sink) {
    out_.reserve(kPiece + 4096);
  }
  fmt::memory_buffer& buffer() { return out_; }
  void flush() {
    if (sink_ == nullptr || out_.size() == 0) return;
    (*sink_)(std::string_view(out_.data(), out_.size()));
    out_.clear();
  }

 private:
  const std::function<void(std::string_view)>* sink_;
  fmt::memory_buffer out_;
};

}  // namespace

void trajectory_csv_pieces(const RunResult& r, const std::function<void(std::string_view)>& sink) {
  Pieces p(&sink);
  append_header(p.buffer(), false, r.extra_columns);
  append_rows(p.buffer(), r, "", r.extra_columns.size(), [&] { p.flush(); });
  p.flush();
}

std::string trajectory_to_csv(const RunResult& r) {
  std::string text;
  trajectory_csv_pieces(r, [&](std::string_view piece) { text.append(piece); });
  return text;
}

void trajectory_csv_pieces(const FleetResult& f,
                           const std::function<void(std::string_view)>& sink) {
  Pieces p(&sink);
  const std::vector<std::string> extras = fleet_extras(f);
  append_header(p.buffer(), true, extras);
  std::string suffix;
  for (const RunResult& r : f.robots) {
    suffix.assign(1, ',');
    suffix += csv_field(r.scenario);
    append_rows(p.buffer(), r, suffix, extras.size(), [&] { p.flush(); });
  }
  p.flush();
}

std::string trajectory_to_csv(const FleetResult& f) {
  std::string text;
  trajectory_csv_pieces(f, [&](std::string_view piece) { text.append(piece); });
  return text;
}

namespace {

/// A number for a CSV field: empty when it is not finite.
std::string number(double v) {
  return std::isfinite(v) ? fmt::format("{}", v) : std::string();
}

std::string name_or_index(const std::vector<std::string>& names, int index, const char* fallback) {
  if (index >= 0 && static_cast<std::size_t>(index) < names.size())
    return csv_field(names[static_cast<std::size_t>(index)]);
  return fallback + std::to_string(index);
}

void append_transitions(fmt::memory_buffer& out, const RunResult& r, std::string_view robot) {
  for (std::size_t i = 0; i < r.transitions.size(); ++i) {
    const Transition& t = r.transitions[i];
    const double x = i < r.transition_x.size() ? r.transition_x[i] : std::nan("");
    const double y = i < r.transition_y.size() ? r.transition_y[i] : std::nan("");
    fmt::format_to(std::back_inserter(out), "{},{},{},{},{},{},{}\n", t.time, robot,
                   name_or_index(r.mode_names, t.from, "mode_"),
                   name_or_index(r.mode_names, t.to, "mode_"),
                   t.edge >= 0 ? name_or_index(r.guard_names, t.edge, "edge_") : std::string(),
                   number(x), number(y));
  }
}

constexpr const char* kTransitionsHeader = "t,robot,from,to,guard,x,y\n";

}  // namespace

std::string transitions_to_csv(const RunResult& r, std::string_view robot) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}", kTransitionsHeader);
  append_transitions(out, r, csv_field(robot));
  return fmt::to_string(out);
}

std::string transitions_to_csv(const FleetResult& f) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "{}", kTransitionsHeader);
  // Every robot's transitions in time order (robot order breaks ties).
  struct Entry {
    double t;
    std::size_t robot, index;
  };
  std::vector<Entry> all;
  for (std::size_t k = 0; k < f.robots.size(); ++k)
    for (std::size_t i = 0; i < f.robots[k].transitions.size(); ++i)
      all.push_back({f.robots[k].transitions[i].time, k, i});
  std::stable_sort(all.begin(), all.end(),
                   [](const Entry& a, const Entry& b) { return a.t < b.t; });
  for (const Entry& e : all) {
    const RunResult& r = f.robots[e.robot];
    const Transition& t = r.transitions[e.index];
    fmt::format_to(
        std::back_inserter(out), "{},{},{},{},{},{},{}\n", t.time, csv_field(r.scenario),
        name_or_index(r.mode_names, t.from, "mode_"), name_or_index(r.mode_names, t.to, "mode_"),
        t.edge >= 0 ? name_or_index(r.guard_names, t.edge, "edge_") : std::string(),
        number(e.index < r.transition_x.size() ? r.transition_x[e.index] : std::nan("")),
        number(e.index < r.transition_y.size() ? r.transition_y[e.index] : std::nan("")));
  }
  return fmt::to_string(out);
}

}  // namespace floornav
