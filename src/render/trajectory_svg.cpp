#include "floornav/render/trajectory_svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <string_view>
#include <vector>

#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"

namespace floornav {
namespace svg_detail {

/// A length or coordinate in pixels, printed with at most two decimals ("12.5", "-3", "0.07").
struct Px {
  double v;
};

/// Text to be placed in XML content or an attribute, escaped on output.
struct Xml {
  std::string_view text;
};

}  // namespace svg_detail
}  // namespace floornav

template <>
struct fmt::formatter<floornav::svg_detail::Px> {
  constexpr auto parse(format_parse_context& ctx) { return ctx.begin(); }
  template <class Context>
  auto format(const floornav::svg_detail::Px& p, Context& ctx) const {
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
struct fmt::formatter<floornav::svg_detail::Xml> {
  constexpr auto parse(format_parse_context& ctx) { return ctx.begin(); }
  template <class Context>
  auto format(const floornav::svg_detail::Xml& x, Context& ctx) const {
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

namespace floornav {

namespace {

using svg_detail::Px;
using svg_detail::Xml;

constexpr double kMapMaxWidth = 860.0;    ///< px available to the world's width
constexpr double kMapMaxHeight = 1000.0;  ///< px available to the world's height
constexpr double kMapMargin = 22.0;       ///< px between the world's extent and the map frame
constexpr double kPad = 20.0;             ///< px around everything
constexpr double kTitleHeight = 58.0;     ///< px for the title and the subtitle
constexpr double kMinCanvasWidth = 640.0;
constexpr std::size_t kMaxPathPoints = 5000;
/// Fleets up to this size have each robot named beside its start.
constexpr std::size_t kMaxNamedRobots = 40;
constexpr std::size_t kMaxSwitchMarkers = 2000;
constexpr double kSwitchSpacing = 8.0;   ///< px between two switch markers, at least
constexpr double kMinRobotRadius = 6.0;  ///< px: a tiny robot is still drawn visibly
constexpr std::int64_t kMaxGridCells = 4'000'000;
constexpr double kMinPointSpacing = 0.5;  ///< px: closer path samples are dropped
constexpr double kLegendFont = 12.0;
constexpr double kLegendRow = 22.0;
constexpr const char* kFont = "Helvetica, Arial, sans-serif";

constexpr std::array<std::pair<std::string_view, std::string_view>, 6> kModeColors{{
    {"go_to_goal", "#1f77b4"},
    {"follow_boundary_cw", "#ff7f0e"},
    {"follow_boundary_ccw", "#2ca02c"},
    {"avoid_obstacle", "#d62728"},
    {"blended", "#9467bd"},
    {"stop", "#000000"},
}};
constexpr std::array<std::string_view, 5> kSpareColors{"#8c564b", "#e377c2", "#17becf", "#bcbd22",
                                                       "#7f7f7f"};

constexpr const char* kGoalFill = "#f4b400";
constexpr const char* kGoalStroke = "#8a6d00";
constexpr const char* kObstacleFill = "#c9ccd1";
constexpr const char* kObstacleStroke = "#6b7079";
constexpr const char* kGridFill = "#a9adb3";
constexpr const char* kWall = "#37474f";

/// An axis-aligned box that grows to hold what is added (metres).
struct Extent {
  double xmin{std::numeric_limits<double>::infinity()};
  double ymin{std::numeric_limits<double>::infinity()};
  double xmax{-std::numeric_limits<double>::infinity()};
  double ymax{-std::numeric_limits<double>::infinity()};

  void add(double x, double y, double pad = 0.0) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    xmin = std::min(xmin, x - pad);
    ymin = std::min(ymin, y - pad);
    xmax = std::max(xmax, x + pad);
    ymax = std::max(ymax, y + pad);
  }
  bool valid() const { return xmin <= xmax && ymin <= ymax; }
};

/// World (metres, y up) to picture (pixels, y down).
struct View {
  double xmin{0.0}, ymax{0.0};
  double scale{1.0};  ///< px per metre
  double left{0.0}, top{0.0};
  double width{0.0}, height{0.0};  ///< px of the world's extent

  double x(double wx) const { return left + (wx - xmin) * scale; }
  double y(double wy) const { return top + (ymax - wy) * scale; }
};

using Out = std::back_insert_iterator<fmt::memory_buffer>;

bool world_has_content(const World& w) {
  return w.bounds() || !w.circles().empty() || !w.polygons().empty() || w.grid() != nullptr;
}

const OccupancyGrid* grid_of(const Scenario& s) {
  return s.world ? s.world->grid() : nullptr;
}

void add_grid_extent(Extent& e, const OccupancyGrid& g) {
  const double w = g.width() * g.resolution();
  const double h = g.height() * g.resolution();
  for (const Vec2& corner : {Vec2(0, 0), Vec2(w, 0), Vec2(0, h), Vec2(w, h)}) {
    const Vec2 p = g.origin().transform_point(corner);
    e.add(p.x(), p.y());
  }
}

/// Everything that must be in the picture: the world, the start, the goals, the path.
/// One robot's run as the picture draws it: the robot's task (its body, start, goals and
/// epsilon) and its result.
struct Track {
  const RobotTask* task;
  const RunResult* r;
};

Extent picture_extent(const Scenario& world_s, std::span<const Track> tracks) {
  Extent e;
  if (world_s.world && world_has_content(*world_s.world)) {
    const Box2& box = world_s.world->extent();
    e.add(box.min.x(), box.min.y());
    e.add(box.max.x(), box.max.y());
  }
  if (const OccupancyGrid* g = grid_of(world_s)) add_grid_extent(e, *g);
  double body = 0.0;
  for (const Track& t : tracks) {
    const RobotTask& s = *t.task;
    const RunResult& r = *t.r;
    body = std::max(body, std::max(0.0, s.robot.body_radius));
    const double b = std::max(0.0, s.robot.body_radius);
    e.add(s.start.position.x(), s.start.position.y(), b);
    for (const Vec2& goal : s.goals)
      e.add(goal.x(), goal.y(), std::max(0.0, s.controller.params.epsilon));
    for (const TrajectorySample& p : r.trajectory) e.add(p.x, p.y, b);
    e.add(r.final_x, r.final_y, b);
  }
  if (!e.valid()) e = Extent{-1.0, -1.0, 1.0, 1.0};
  // A straight run in an empty world would give a sliver: keep both sides in proportion.
  const double span = std::max({e.xmax - e.xmin, e.ymax - e.ymin, 4.0 * body, 0.2});
  const double min_side = 0.25 * span;
  for (auto [lo, hi] : {std::pair{&e.xmin, &e.xmax}, std::pair{&e.ymin, &e.ymax}}) {
    const double grow = 0.5 * std::max(0.0, min_side - (*hi - *lo));
    *lo -= grow;
    *hi += grow;
  }
  return e;
}

std::string_view color_for_mode(const RunResult& r, int mode) {
  int spare = 0;
  for (int m = 0; m < static_cast<int>(r.mode_names.size()); ++m) {
    const std::string& name = r.mode_names[static_cast<std::size_t>(m)];
    const bool known = std::any_of(kModeColors.begin(), kModeColors.end(),
                                   [&](const auto& kc) { return kc.first == name; });
    if (m == mode) return mode_color(name, spare);
    if (!known) ++spare;
  }
  return kSpareColors[static_cast<std::size_t>(std::abs(mode)) % kSpareColors.size()];
}

std::string mode_label(const RunResult& r, int mode) {
  if (mode >= 0 && static_cast<std::size_t>(mode) < r.mode_names.size())
    return r.mode_names[static_cast<std::size_t>(mode)];
  return "mode_" + std::to_string(mode);
}

// ---- the world -------------------------------------------------------------------------------

void draw_background(Out out, const Scenario& s, const View& v, double canvas_w, double canvas_h) {
  fmt::format_to(out,
                 R"(<rect width="{}" height="{}" fill="#ffffff"/>)"
                 "\n",
                 Px{canvas_w}, Px{canvas_h});
  const double fx = v.left - kMapMargin;
  const double fy = v.top - kMapMargin;
  const double fw = v.width + 2 * kMapMargin;
  const double fh = v.height + 2 * kMapMargin;
  const bool bounded = s.world && s.world->bounds();
  // Outside the bounds is solid: a light grey, so the free floor stands out.
  fmt::format_to(out,
                 R"(<rect x="{}" y="{}" width="{}" height="{}" fill="{}" stroke="#d5d8dc"/>)"
                 "\n",
                 Px{fx}, Px{fy}, Px{fw}, Px{fh}, bounded ? "#eceef0" : "#fdfdfd");
  if (bounded) {
    const Box2& b = *s.world->bounds();
    fmt::format_to(out,
                   R"(<rect x="{}" y="{}" width="{}" height="{}" fill="#ffffff"/>)"
                   "\n",
                   Px{v.x(b.min.x())}, Px{v.y(b.max.y())}, Px{b.size().x() * v.scale},
                   Px{b.size().y() * v.scale});
  }
}

void draw_walls(Out out, const Scenario& s, const View& v) {
  if (!s.world || !s.world->bounds()) return;
  const Box2& b = *s.world->bounds();
  // The wall is drawn outside the bounds, so that its inner edge is where the robot collides.
  const double t = std::clamp(0.03 * v.scale, 4.0, 10.0);
  fmt::format_to(out,
                 R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="{}" )"
                 R"(stroke-width="{}" stroke-linejoin="miter"/>)"
                 "\n",
                 Px{v.x(b.min.x()) - t / 2}, Px{v.y(b.max.y()) - t / 2},
                 Px{b.size().x() * v.scale + t}, Px{b.size().y() * v.scale + t}, kWall, Px{t});
}

/// The grid's occupied cells as one path: one rectangle per horizontal run of occupied cells,
/// in cell units under a transform (so coordinates are small integers). Grids over kMaxGridCells
/// are drawn with k x k blocks, a block being occupied when any of its cells is.
void draw_grid(Out out, const OccupancyGrid& g, const View& v) {
  const std::int64_t cells = static_cast<std::int64_t>(g.width()) * g.height();
  if (cells <= 0 || g.occupied_count() == 0) return;
  int k = 1;
  while ((static_cast<std::int64_t>(g.width() + k - 1) / k) *
             ((static_cast<std::int64_t>(g.height()) + k - 1) / k) >
         kMaxGridCells)
    ++k;
  const int w = (g.width() + k - 1) / k;
  const int h = (g.height() + k - 1) / k;
  std::vector<std::uint8_t> occ(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
  for (int iy = 0; iy < g.height(); ++iy)
    for (int ix = 0; ix < g.width(); ++ix)
      if (g.occupied(ix, iy))
        occ[static_cast<std::size_t>(iy / k) * static_cast<std::size_t>(w) +
            static_cast<std::size_t>(ix / k)] = 1;

  // Cell (u, v) -> world origin + R(yaw) (u, v) res k -> pixels (y flipped).
  const double cell = g.resolution() * k * v.scale;
  const double c = std::cos(g.origin().theta);
  const double s = std::sin(g.origin().theta);
  const Vec2& o = g.origin().position;
  fmt::format_to(
      out,
      R"svg(<path fill="{}" transform="matrix({:.6g} {:.6g} {:.6g} {:.6g} {:.6g} {:.6g})" d=")svg",
      kGridFill, cell * c, -cell * s, -cell * s, -cell * c, v.x(o.x()), v.y(o.y()));
  for (int iy = 0; iy < h; ++iy) {
    const std::uint8_t* row =
        occ.data() + static_cast<std::size_t>(iy) * static_cast<std::size_t>(w);
    for (int ix = 0; ix < w;) {
      if (!row[ix]) {
        ++ix;
        continue;
      }
      int end = ix;
      while (end < w && row[end]) ++end;
      fmt::format_to(out, "M{} {}h{}v1h-{}z", ix, iy, end - ix, end - ix);
      ix = end;
    }
  }
  fmt::format_to(out, "\"/>\n");
}

void draw_obstacles(Out out, const World& w, const View& v) {
  if (w.polygons().empty() && w.circles().empty()) return;
  fmt::format_to(out,
                 R"(<g fill="{}" stroke="{}" stroke-width="1.5" stroke-linejoin="round">)"
                 "\n",
                 kObstacleFill, kObstacleStroke);
  for (const auto& poly : w.polygons()) {
    if (poly.size() < 2) continue;
    fmt::format_to(out, R"(<polygon points=")");
    for (std::size_t i = 0; i < poly.size(); ++i)
      fmt::format_to(out, "{}{},{}", i ? " " : "", Px{v.x(poly[i].x())}, Px{v.y(poly[i].y())});
    fmt::format_to(out, "\"/>\n");
  }
  for (const Circle& c : w.circles())
    fmt::format_to(out,
                   R"(<circle cx="{}" cy="{}" r="{}"/>)"
                   "\n",
                   Px{v.x(c.center.x())}, Px{v.y(c.center.y())},
                   Px{std::max(c.radius * v.scale, 2.0)});
  fmt::format_to(out, "</g>\n");
}

// ---- the run ---------------------------------------------------------------------------------

struct PathRun {
  int mode{0};
  std::vector<std::array<double, 2>> points;  ///< px
};

/// The path split where the mode changes (each piece starting where the previous one ended, so
/// the line is unbroken), with samples closer than kMinPointSpacing dropped and, past
/// kMaxPathPoints, thinned evenly. The first and last sample of every piece are always kept.
std::vector<PathRun> path_runs(const RunResult& r, const View& v, std::size_t max_points) {
  std::vector<PathRun> runs;
  bool broken = true;  // true at the start and after a non-finite sample
  bool has_pending = false;
  std::array<double, 2> pending{};
  auto close_run = [&] {
    if (has_pending && !runs.empty()) runs.back().points.push_back(pending);
    has_pending = false;
  };
  for (const TrajectorySample& s : r.trajectory) {
    if (!std::isfinite(s.x) || !std::isfinite(s.y)) {
      close_run();
      broken = true;
      continue;
    }
    const std::array<double, 2> p{v.x(s.x), v.y(s.y)};
    if (broken || runs.empty() || runs.back().mode != s.mode) {
      close_run();
      PathRun run;
      run.mode = s.mode;
      if (!broken && !runs.empty()) run.points.push_back(runs.back().points.back());
      runs.push_back(std::move(run));
      broken = false;
    }
    auto& pts = runs.back().points;
    if (!pts.empty() && std::hypot(p[0] - pts.back()[0], p[1] - pts.back()[1]) < kMinPointSpacing) {
      pending = p;
      has_pending = true;
      continue;
    }
    pts.push_back(p);
    has_pending = false;
  }
  close_run();

  std::size_t total = 0;
  for (const PathRun& run : runs) total += run.points.size();
  if (total > max_points) {
    const std::size_t stride = (total + max_points - 1) / max_points;
    for (PathRun& run : runs) {
      auto& pts = run.points;
      if (pts.size() <= 2) continue;
      std::vector<std::array<double, 2>> kept;
      kept.reserve(pts.size() / stride + 2);
      for (std::size_t i = 0; i + 1 < pts.size(); i += stride) kept.push_back(pts[i]);
      kept.push_back(pts.back());
      pts = std::move(kept);
    }
  }
  return runs;
}

void draw_path(Out out, const RunResult& r, const View& v, std::size_t max_points) {
  const std::vector<PathRun> runs = path_runs(r, v, max_points);
  if (runs.empty()) return;
  fmt::format_to(out, R"(<g fill="none" stroke-width="2.5" stroke-linecap="round" )"
                      R"(stroke-linejoin="round">)"
                      "\n");
  for (const PathRun& run : runs) {
    if (run.points.empty()) continue;
    fmt::format_to(out, R"(<polyline stroke="{}" points=")", color_for_mode(r, run.mode));
    for (std::size_t i = 0; i < run.points.size(); ++i)
      fmt::format_to(out, "{}{},{}", i ? " " : "", Px{run.points[i][0]}, Px{run.points[i][1]});
    // A single point would draw nothing: repeat it, and the round cap makes a dot.
    if (run.points.size() == 1)
      fmt::format_to(out, " {},{}", Px{run.points[0][0]}, Px{run.points[0][1]});
    fmt::format_to(out, "\"/>\n");
  }
  fmt::format_to(out, "</g>\n");
}

void draw_switch_marker(Out out, double x, double y) {
  fmt::format_to(out,
                 R"(<circle cx="{}" cy="{}" r="3.2"/>)"
                 "\n",
                 Px{x}, Px{y});
}

/// One hollow circle per switch point; a switch within kSwitchSpacing px of one already drawn is
/// left out, so that chatter shows as a chain of markers rather than a black smear.
void draw_switches(Out out, const RunResult& r, const View& v) {
  const std::size_t n = std::min(r.transition_x.size(), r.transition_y.size());
  if (n == 0) return;
  fmt::format_to(out, R"(<g fill="#ffffff" fill-opacity="0.9" stroke="#222222" )"
                      R"(stroke-width="1.3">)"
                      "\n");
  // Markers drawn so far, bucketed in cells of kSwitchSpacing px over the map.
  const int cols = static_cast<int>(v.width / kSwitchSpacing) + 3;
  const int rows = static_cast<int>(v.height / kSwitchSpacing) + 3;
  std::vector<std::vector<std::array<double, 2>>> cells(static_cast<std::size_t>(cols * rows));
  auto cell_of = [&](double px, double count) {
    return std::clamp(static_cast<int>(std::floor(px / kSwitchSpacing)) + 1, 0,
                      static_cast<int>(count) - 1);
  };
  std::size_t drawn = 0;
  for (std::size_t i = 0; i < n && drawn < kMaxSwitchMarkers; ++i) {
    if (!std::isfinite(r.transition_x[i]) || !std::isfinite(r.transition_y[i])) continue;
    const std::array<double, 2> p{v.x(r.transition_x[i]), v.y(r.transition_y[i])};
    const int cx = cell_of(p[0] - v.left, cols);
    const int cy = cell_of(p[1] - v.top, rows);
    bool crowded = false;
    for (int y = std::max(cy - 1, 0); y <= std::min(cy + 1, rows - 1) && !crowded; ++y)
      for (int x = std::max(cx - 1, 0); x <= std::min(cx + 1, cols - 1) && !crowded; ++x)
        for (const auto& q : cells[static_cast<std::size_t>(y * cols + x)])
          if (std::hypot(p[0] - q[0], p[1] - q[1]) < kSwitchSpacing) crowded = true;
    if (crowded) continue;
    cells[static_cast<std::size_t>(cy * cols + cx)].push_back(p);
    ++drawn;
    draw_switch_marker(out, p[0], p[1]);
  }
  fmt::format_to(out, "</g>\n");
}

/// A disc of radius `r` px with a tick from the centre along `theta` (world radians).
void draw_robot(Out out, double x, double y, double r, double theta, std::string_view fill,
                double fill_opacity, std::string_view stroke) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  if (!std::isfinite(theta)) theta = 0.0;
  fmt::format_to(out,
                 R"(<circle cx="{}" cy="{}" r="{}" fill="{}" fill-opacity="{}" stroke="{}" )"
                 R"(stroke-width="1.6"/>)"
                 "\n",
                 Px{x}, Px{y}, Px{r}, fill, fill_opacity, stroke);
  fmt::format_to(out,
                 R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="1.8" )"
                 R"(stroke-linecap="round"/>)"
                 "\n",
                 Px{x}, Px{y}, Px{x + r * std::cos(theta)}, Px{y - r * std::sin(theta)}, stroke);
}

void draw_flag(Out out, double x, double y, double size) {
  const double pole = 1.6 * size;
  fmt::format_to(out,
                 R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#333333" stroke-width="1.6" )"
                 R"(stroke-linecap="round"/>)"
                 "\n",
                 Px{x}, Px{y}, Px{x}, Px{y - pole});
  fmt::format_to(out,
                 R"(<polygon points="{},{} {},{} {},{}" fill="{}" stroke="{}" stroke-width="1" )"
                 R"(stroke-linejoin="round"/>)"
                 "\n",
                 Px{x}, Px{y - pole}, Px{x + size}, Px{y - pole + 0.3 * size}, Px{x},
                 Px{y - pole + 0.6 * size}, kGoalFill, kGoalStroke);
  fmt::format_to(out,
                 R"(<circle cx="{}" cy="{}" r="2" fill="#333333"/>)"
                 "\n",
                 Px{x}, Px{y});
}

void draw_goal_areas(Out out, const RobotTask& s, const View& v) {
  const double eps = std::max(0.0, s.controller.params.epsilon) * v.scale;
  for (const Vec2& g : s.goals) {
    if (!is_finite(g)) continue;
    fmt::format_to(out,
                   R"(<circle cx="{}" cy="{}" r="{}" fill="{}" fill-opacity="0.18" stroke="{}" )"
                   R"(stroke-width="1.2" stroke-dasharray="4 3"/>)"
                   "\n",
                   Px{v.x(g.x())}, Px{v.y(g.y())}, Px{std::max(eps, 3.0)}, kGoalFill, kGoalStroke);
  }
}

void draw_goal_flags(Out out, const RobotTask& s, const View& v) {
  for (std::size_t i = 0; i < s.goals.size(); ++i) {
    const Vec2& g = s.goals[i];
    if (!is_finite(g)) continue;
    draw_flag(out, v.x(g.x()), v.y(g.y()), 13.0);
    if (s.goals.size() > 1)
      fmt::format_to(out,
                     R"(<text x="{}" y="{}" font-family="{}" font-size="11" font-weight="bold" )"
                     R"(fill="#5c4800">{}</text>)"
                     "\n",
                     Px{v.x(g.x()) + 15}, Px{v.y(g.y()) - 12}, kFont, i + 1);
  }
}

// ---- title, legend, scale bar ----------------------------------------------------------------

double text_width(std::string_view text, double font_size) {
  return 0.58 * font_size * static_cast<double>(text.size());
}

/// The round length (1, 2 or 5 times a power of ten, metres) whose bar is at most 160 px.
double scale_bar_length(double px_per_m) {
  double best = 0.0;
  for (int e = -4; e <= 6; ++e)
    for (double m : {1.0, 2.0, 5.0}) {
      const double len = m * std::pow(10.0, e);
      if (len * px_per_m <= 160.0) best = len;
    }
  return best > 0.0 ? best : 1e-4;
}

enum class LegendIcon { Mode, Start, Goal, Switch, End };

struct LegendItem {
  LegendIcon icon;
  std::string label;
  std::string_view color;
};

std::vector<LegendItem> legend_items(std::span<const Track> tracks) {
  std::vector<LegendItem> items;
  auto add_mode = [&](const RunResult& r, int m) {
    std::string label = mode_label(r, m);
    for (const LegendItem& it : items)
      if (it.label == label) return;
    items.push_back({LegendIcon::Mode, std::move(label), color_for_mode(r, m)});
  };
  bool goals = false, many_goals = false, switches = false, collided = false;
  for (const Track& t : tracks) {
    const RunResult& r = *t.r;
    const int n = static_cast<int>(std::max(r.mode_names.size(), r.mode_time.size()));
    std::vector<bool> used(static_cast<std::size_t>(std::max(n, 0)), false);
    std::vector<int> extra;  // modes in the trajectory beyond the named ones
    for (const TrajectorySample& p : r.trajectory) {
      if (p.mode >= 0 && p.mode < n)
        used[static_cast<std::size_t>(p.mode)] = true;
      else if (std::find(extra.begin(), extra.end(), p.mode) == extra.end())
        extra.push_back(p.mode);
    }
    for (std::size_t m = 0; m < r.mode_time.size(); ++m)
      if (r.mode_time[m] > 0.0) used[m] = true;
    for (int m = 0; m < n; ++m)
      if (used[static_cast<std::size_t>(m)]) add_mode(r, m);
    for (int m : extra) add_mode(r, m);
    goals = goals || !t.task->goals.empty();
    many_goals = many_goals || t.task->goals.size() > 1 || (goals && tracks.size() > 1);
    switches = switches || !r.transition_x.empty();
    collided = collided || r.collided;
  }
  items.push_back({LegendIcon::Start, "start", ""});
  if (goals) items.push_back({LegendIcon::Goal, many_goals ? "goals" : "goal", ""});
  if (switches) items.push_back({LegendIcon::Switch, "mode switch", ""});
  items.push_back({LegendIcon::End, collided ? "end (collision)" : "end", ""});
  return items;
}

constexpr double kIconWidth = 24.0;

double legend_item_width(const LegendItem& item) {
  return kIconWidth + 6.0 + text_width(item.label, kLegendFont) + 18.0;
}

/// Rows of legend items that fit in `width` px.
std::vector<std::vector<const LegendItem*>> legend_rows(const std::vector<LegendItem>& items,
                                                        double width) {
  std::vector<std::vector<const LegendItem*>> rows(1);
  double used = 0.0;
  for (const LegendItem& item : items) {
    const double w = legend_item_width(item);
    if (!rows.back().empty() && used + w > width) {
      rows.emplace_back();
      used = 0.0;
    }
    rows.back().push_back(&item);
    used += w;
  }
  return rows;
}

void draw_legend_icon(Out out, const LegendItem& item, bool collided, double x, double cy) {
  switch (item.icon) {
    case LegendIcon::Mode:
      fmt::format_to(out,
                     R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="4" )"
                     R"(stroke-linecap="round"/>)"
                     "\n",
                     Px{x + 2}, Px{cy}, Px{x + kIconWidth - 2}, Px{cy}, item.color);
      break;
    case LegendIcon::Start:
      draw_robot(out, x + kIconWidth / 2, cy, 6.5, 0.0, "#ffffff", 1.0, "#333333");
      break;
    case LegendIcon::Goal:
      draw_flag(out, x + kIconWidth / 2 - 4, cy + 7, 8.5);
      break;
    case LegendIcon::Switch:
      fmt::format_to(out,
                     R"(<circle cx="{}" cy="{}" r="3.2" fill="#ffffff" stroke="#222222" )"
                     R"(stroke-width="1.3"/>)"
                     "\n",
                     Px{x + kIconWidth / 2}, Px{cy});
      break;
    case LegendIcon::End:
      if (collided)
        draw_robot(out, x + kIconWidth / 2, cy, 6.5, 0.0, "#d62728", 0.85, "#7f0000");
      else
        draw_robot(out, x + kIconWidth / 2, cy, 6.5, 0.0, "#90a4ae", 0.9, "#263238");
      break;
  }
}

void draw_scale_bar(Out out, double right, double cy, double px_per_m) {
  const double len_m = scale_bar_length(px_per_m);
  const double len = len_m * px_per_m;
  const double x0 = right - len;
  fmt::format_to(out,
                 R"(<path d="M{} {}v6h{}v-6" fill="none" stroke="#333333" stroke-width="1.8" )"
                 R"(stroke-linejoin="miter"/>)"
                 "\n",
                 Px{x0}, Px{cy - 3}, Px{len});
  fmt::format_to(out,
                 R"(<text x="{}" y="{}" font-family="{}" font-size="{}" fill="#333333" )"
                 R"(text-anchor="end">{} m</text>)"
                 "\n",
                 Px{x0 - 6}, Px{cy + 4}, kFont, kLegendFont, len_m);
}

}  // namespace

std::string_view mode_color(std::string_view name, int fallback_index) {
  for (const auto& [mode, color] : kModeColors)
    if (mode == name) return color;
  return kSpareColors[static_cast<std::size_t>(std::abs(fallback_index)) % kSpareColors.size()];
}

namespace {

constexpr const char* kPersonColor = "#7b3fa0";
constexpr const char* kForkliftColor = "#b35900";
constexpr std::size_t kMaxCrowdPathPoints = 500;  ///< per person or forklift

/// People's paths (thin purple) with their bodies where they ended, forklifts' paths (brown,
/// dashed) with their footprints where they ended.
void draw_crowd(Out out, const CrowdResult& c, const View& v) {
  auto path = [&](const CrowdTrack& t, const char* color, const char* extra) {
    if (t.samples.size() < 2) return;
    const std::size_t every = std::max<std::size_t>(1, t.samples.size() / kMaxCrowdPathPoints);
    fmt::format_to(out,
                   R"(<polyline fill="none" stroke="{}" stroke-width="1.2" )"
                   R"(stroke-opacity="0.55" {}points=")",
                   color, extra);
    for (std::size_t k = 0; k < t.samples.size(); k += every)
      fmt::format_to(out, "{},{} ", Px{v.x(t.samples[k].x)}, Px{v.y(t.samples[k].y)});
    fmt::format_to(out, "{},{}\"/>\n", Px{v.x(t.samples.back().x)}, Px{v.y(t.samples.back().y)});
  };
  for (const CrowdTrack& t : c.forklifts) path(t, kForkliftColor, R"(stroke-dasharray="6 4" )");
  for (const CrowdTrack& t : c.people) path(t, kPersonColor, "");
  for (const CrowdTrack& t : c.forklifts) {
    if (t.samples.empty()) continue;
    const CrowdSample& e = t.samples.back();
    const auto corners = OrientedBox::make(Vec2(e.x, e.y), t.size, e.theta).corners();
    fmt::format_to(out,
                   R"(<polygon fill="{}" fill-opacity="0.35" stroke="{}" stroke-width="1.5" )"
                   R"(points=")",
                   kForkliftColor, kForkliftColor);
    for (const Vec2& q : corners) fmt::format_to(out, "{},{} ", Px{v.x(q.x())}, Px{v.y(q.y())});
    fmt::format_to(out, "\"/>\n");
  }
  for (const CrowdTrack& t : c.people) {
    if (t.samples.empty()) continue;
    const CrowdSample& e = t.samples.back();
    fmt::format_to(out,
                   R"(<circle cx="{}" cy="{}" r="{}" fill="{}" fill-opacity="0.45" stroke="{}" )"
                   R"(stroke-width="1.2"/>)"
                   "\n",
                   Px{v.x(e.x)}, Px{v.y(e.y)}, Px{std::max(0.5 * t.size.x() * v.scale, 3.0)},
                   kPersonColor, kPersonColor);
  }
}

/// The picture of one or more robots in one world: `world_s` gives the world, `tracks` the
/// robots; `title` and `numbers` the two lines of text at the top.
std::string render_tracks(const Scenario& world_s, std::span<const Track> tracks,
                          const std::string& title, const std::string& numbers,
                          const CrowdResult* crowd = nullptr) {
  const Extent e = picture_extent(world_s, tracks);
  const double w_m = e.xmax - e.xmin;
  const double h_m = e.ymax - e.ymin;
  View v;
  v.scale = std::min(kMapMaxWidth / w_m, kMapMaxHeight / h_m);
  v.width = w_m * v.scale;
  v.height = h_m * v.scale;
  v.xmin = e.xmin;
  v.ymax = e.ymax;

  const double canvas_w = std::max(v.width + 2 * (kPad + kMapMargin), kMinCanvasWidth);
  v.left = 0.5 * (canvas_w - v.width);
  v.top = kTitleHeight + kMapMargin;

  const std::vector<LegendItem> items = legend_items(tracks);
  const double scale_bar_room = 190.0;
  const auto rows = legend_rows(items, canvas_w - 2 * kPad - scale_bar_room);
  const double legend_top = v.top + v.height + kMapMargin + 12.0;
  const double canvas_h = legend_top + static_cast<double>(rows.size()) * kLegendRow + kPad;
  bool any_collided = false;
  for (const Track& t : tracks) any_collided = any_collided || t.r->collided;
  // Path points are shared among the robots, so that a big fleet's picture stays small.
  const std::size_t max_points =
      std::max<std::size_t>(kMaxPathPoints / std::max<std::size_t>(tracks.size(), 1), 50);
  const bool fleet = tracks.size() > 1;

  fmt::memory_buffer buf;
  buf.reserve(64 * 1024);
  Out out(buf);
  fmt::format_to(out,
                 R"(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" )"
                 R"(viewBox="0 0 {} {}">)"
                 "\n",
                 Px{canvas_w}, Px{canvas_h}, Px{canvas_w}, Px{canvas_h});
  fmt::format_to(out, "<title>{}</title>\n", Xml{world_s.name});

  draw_background(out, world_s, v, canvas_w, canvas_h);
  if (const OccupancyGrid* g = grid_of(world_s)) draw_grid(out, *g, v);
  if (world_s.world) draw_obstacles(out, *world_s.world, v);
  draw_walls(out, world_s, v);
  if (crowd) draw_crowd(out, *crowd, v);
  for (const Track& t : tracks) draw_goal_areas(out, *t.task, v);
  for (const Track& t : tracks) draw_path(out, *t.r, v, max_points);
  for (const Track& t : tracks) draw_switches(out, *t.r, v);

  for (const Track& t : tracks) {
    const RobotTask& s = *t.task;
    const RunResult& r = *t.r;
    const double body_px = std::max(s.robot.body_radius * v.scale, kMinRobotRadius);
    draw_robot(out, v.x(s.start.position.x()), v.y(s.start.position.y()), body_px, s.start.theta,
               "#ffffff", 0.85, "#333333");
    if (r.collided)
      draw_robot(out, v.x(r.final_x), v.y(r.final_y), body_px, r.final_theta, "#d62728", 0.85,
                 "#7f0000");
    else
      draw_robot(out, v.x(r.final_x), v.y(r.final_y), body_px, r.final_theta, "#90a4ae", 0.9,
                 "#263238");
  }
  for (const Track& t : tracks) draw_goal_flags(out, *t.task, v);  // over the final bodies
  // A small fleet's robots are named at their start.
  if (fleet && tracks.size() <= kMaxNamedRobots)
    for (const Track& t : tracks) {
      const RobotTask& s = *t.task;
      const double body_px = std::max(s.robot.body_radius * v.scale, kMinRobotRadius);
      fmt::format_to(out,
                     R"(<text x="{}" y="{}" font-family="{}" font-size="11" fill="#222222" )"
                     R"(text-anchor="middle">{}</text>)"
                     "\n",
                     Px{v.x(s.start.position.x())}, Px{v.y(s.start.position.y()) - body_px - 4},
                     kFont, Xml{t.r->scenario});
    }

  fmt::format_to(out,
                 R"(<text x="{}" y="28" font-family="{}" font-size="17" font-weight="bold" )"
                 R"(fill="#222222">{}</text>)"
                 "\n",
                 Px{kPad}, kFont, Xml{title});
  fmt::format_to(out,
                 R"(<text x="{}" y="47" font-family="{}" font-size="12" fill="#666666">{}</text>)"
                 "\n",
                 Px{kPad}, kFont, Xml{numbers});

  // Legend rows, then the scale bar at the right of the first row.
  for (std::size_t row = 0; row < rows.size(); ++row) {
    const double cy = legend_top + kLegendRow * (static_cast<double>(row) + 0.5);
    double x = kPad;
    for (const LegendItem* item : rows[row]) {
      draw_legend_icon(out, *item, any_collided, x, cy);
      fmt::format_to(out,
                     R"(<text x="{}" y="{}" font-family="{}" font-size="{}" fill="#333333">{})"
                     R"(</text>)"
                     "\n",
                     Px{x + kIconWidth + 6}, Px{cy + 4}, kFont, kLegendFont, Xml{item->label});
      x += legend_item_width(*item);
    }
  }
  draw_scale_bar(out, canvas_w - kPad, legend_top + 0.5 * kLegendRow, v.scale);

  fmt::format_to(out, "</svg>\n");
  return fmt::to_string(buf);
}

// "+ 0.0" turns -0 into 0; a clearance that rounds to zero must not print as "-0.000".
double shown_clearance(double c) {
  return std::round(c * 1000.0) / 1000.0 + 0.0;
}

}  // namespace

std::string render_trajectory_svg(const Scenario& s, const RunResult& r) {
  const std::string title = fmt::format("{} — {} — {} in {:.2f} s", s.name,
                                        s.robot().controller.kind, to_string(r.status), r.sim_time);
  std::string numbers = fmt::format(
      "path {:.2f} m · min clearance {:.3f} m · {} switch{} · {} steps", r.path_length,
      shown_clearance(r.min_clearance), r.mode_switches, r.mode_switches == 1 ? "" : "es", r.steps);
  if (r.goal_count > 1) numbers += fmt::format(" · goals {}/{}", r.goals_reached, r.goal_count);
  if (r.chatter_episodes > 0) numbers += fmt::format(" · chatter ×{}", r.chatter_episodes);
  const Track track{&s.robot(), &r};
  return render_tracks(s, std::span<const Track>(&track, 1), title, numbers);
}

std::string render_fleet_svg(const Scenario& s, const FleetResult& f) {
  std::vector<Track> tracks;
  for (std::size_t i = 0; i < f.robots.size() && i < s.robots.size(); ++i)
    tracks.push_back({&s.robots[i], &f.robots[i]});
  const std::string title = fmt::format("{} — {} robots — {} in {:.2f} s", s.name, f.robots.size(),
                                        to_string(f.status), f.sim_time);
  const std::string numbers = fmt::format(
      "{} reached · {} collided · deliveries {}/{} · min clearance {:.3f} m · {} steps", f.reached,
      f.collided, f.deliveries, f.delivery_count, shown_clearance(f.min_clearance), f.steps);
  if (f.crowd.empty()) return render_tracks(s, tracks, title, numbers);
  // People (purple) and forklifts (brown) are drawn under the robots.
  const CrowdMetrics& m = f.crowd.metrics;
  const std::string crowd_numbers =
      fmt::format("{} · {} people, {} forklifts · contacts {} / {} · {} intrusions", numbers,
                  f.crowd.people.size(), f.crowd.forklifts.size(), m.person_contacts,
                  m.forklift_contacts, m.intrusions);
  return render_tracks(s, tracks, title, crowd_numbers, &f.crowd);
}

}  // namespace floornav
