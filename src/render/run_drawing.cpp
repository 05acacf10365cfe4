#include "run_drawing.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "floornav/render/palette.hpp"

namespace floornav::render_detail {

namespace {

constexpr std::size_t kMaxSwitchMarkers = 2000;
constexpr double kSwitchSpacing = 8.0;    ///< px between two switch markers, at least
constexpr double kMinPointSpacing = 0.5;  ///< px: closer path samples are dropped

using PixelPoint = std::array<double, 2>;

struct PathRun {
  int mode{0};
  std::vector<PixelPoint> points;  ///< px
};

/// The path split where the mode changes (or only where it is broken, when `by_mode` is off), each
/// piece starting where the previous one ended so the line is unbroken, with samples closer than
/// kMinPointSpacing dropped and, past `max_points`, thinned evenly. The first and last sample of
/// every piece are always kept.
std::vector<PathRun> path_runs(const RunResult& r, const View& v, std::size_t max_points,
                               bool by_mode) {
  std::vector<PathRun> runs;
  bool broken = true;  // true at the start and after a non-finite sample
  bool has_pending = false;
  PixelPoint pending{};
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
    const PixelPoint p{v.x(s.x), v.y(s.y)};
    const int mode = by_mode ? s.mode : 0;
    if (broken || runs.empty() || runs.back().mode != mode) {
      close_run();
      PathRun run;
      run.mode = mode;
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
      std::vector<PixelPoint> kept;
      kept.reserve(pts.size() / stride + 2);
      for (std::size_t i = 0; i + 1 < pts.size(); i += stride) kept.push_back(pts[i]);
      kept.push_back(pts.back());
      pts = std::move(kept);
    }
  }
  return runs;
}

}  // namespace

void draw_path(SvgOut out, const Track& track, const View& v, std::size_t max_points) {
  const RunResult& r = *track.run;
  const bool by_mode = track.color.empty();
  const std::vector<PathRun> runs = path_runs(r, v, max_points, by_mode);
  if (runs.empty()) return;
  fmt::format_to(out,
                 R"(<g fill="none" stroke-width="{}" stroke-linecap="round" )"
                 R"(stroke-linejoin="round">)"
                 "\n",
                 by_mode ? "2.5" : "2");
  for (const PathRun& run : runs) {
    if (run.points.empty()) continue;
    fmt::format_to(out, R"(<polyline stroke="{}" points=")",
                   by_mode ? mode_color_of(r.mode_names, run.mode) : std::string_view(track.color));
    for (std::size_t i = 0; i < run.points.size(); ++i)
      fmt::format_to(out, "{}{},{}", i ? " " : "", Px{run.points[i][0]}, Px{run.points[i][1]});
    // A single point would draw nothing: repeat it, and the round cap makes a dot.
    if (run.points.size() == 1)
      fmt::format_to(out, " {},{}", Px{run.points[0][0]}, Px{run.points[0][1]});
    fmt::format_to(out, "\"/>\n");
  }
  fmt::format_to(out, "</g>\n");
}

void draw_switches(SvgOut out, const RunResult& r, const View& v) {
  const std::size_t n = std::min(r.transition_x.size(), r.transition_y.size());
  if (n == 0) return;
  fmt::format_to(out, R"(<g fill="#ffffff" fill-opacity="0.9" stroke="#222222" )"
                      R"(stroke-width="1.3">)"
                      "\n");
  // Markers drawn so far, bucketed in cells of kSwitchSpacing px over the map.
  const int cols = static_cast<int>(v.width / kSwitchSpacing) + 3;
  const int rows = static_cast<int>(v.height / kSwitchSpacing) + 3;
  std::vector<std::vector<PixelPoint>> cells(static_cast<std::size_t>(cols * rows));
  auto cell_of = [&](double px, double count) {
    return std::clamp(static_cast<int>(std::floor(px / kSwitchSpacing)) + 1, 0,
                      static_cast<int>(count) - 1);
  };
  std::size_t drawn = 0;
  for (std::size_t i = 0; i < n && drawn < kMaxSwitchMarkers; ++i) {
    if (!std::isfinite(r.transition_x[i]) || !std::isfinite(r.transition_y[i])) continue;
    const PixelPoint p{v.x(r.transition_x[i]), v.y(r.transition_y[i])};
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
    fmt::format_to(out,
                   R"(<circle cx="{}" cy="{}" r="3.2"/>)"
                   "\n",
                   Px{p[0]}, Px{p[1]});
  }
  fmt::format_to(out, "</g>\n");
}

void draw_disc_robot(SvgOut out, double x, double y, double r, double theta, std::string_view fill,
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

void draw_body(SvgOut out, const RobotSpec& robot, double x, double y, double theta, const View& v,
               std::string_view fill, double fill_opacity, std::string_view stroke) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  if (!std::isfinite(theta)) theta = 0.0;
  const double reach_px = body_reach(robot) * v.scale;
  if (robot.footprint.size() < 3 || reach_px < kMinRobotRadius) {
    // No footprint, or one too small to see: the disc, at least kMinRobotRadius px.
    draw_disc_robot(out, v.x(x), v.y(y), std::max(robot.body_radius * v.scale, kMinRobotRadius),
                    theta, fill, fill_opacity, stroke);
    return;
  }
  const double c = std::cos(theta), s = std::sin(theta);
  fmt::format_to(out, R"(<polygon points=")");
  for (std::size_t i = 0; i < robot.footprint.size(); ++i) {
    const Vec2& p = robot.footprint[i];
    fmt::format_to(out, "{}{},{}", i ? " " : "", Px{v.x(x + c * p.x() - s * p.y())},
                   Px{v.y(y + s * p.x() + c * p.y())});
  }
  fmt::format_to(out,
                 R"(" fill="{}" fill-opacity="{}" stroke="{}" stroke-width="1.6" )"
                 R"(stroke-linejoin="round"/>)"
                 "\n",
                 fill, fill_opacity, stroke);
  // The heading tick reaches the footprint's front (its farthest point ahead of the centre).
  double front = 0.0;
  for (const Vec2& p : robot.footprint) front = std::max(front, p.x());
  if (!(front > 0.0)) front = robot.body_radius;
  fmt::format_to(out,
                 R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="1.8" )"
                 R"(stroke-linecap="round"/>)"
                 "\n",
                 Px{v.x(x)}, Px{v.y(y)}, Px{v.x(x + front * c)}, Px{v.y(y + front * s)}, stroke);
}

void draw_flag(SvgOut out, double x, double y, double size, std::string_view fill,
               std::string_view stroke) {
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
                 Px{y - pole + 0.6 * size}, fill, stroke);
  fmt::format_to(out,
                 R"(<circle cx="{}" cy="{}" r="2" fill="#333333"/>)"
                 "\n",
                 Px{x}, Px{y});
}

void draw_goal_areas(SvgOut out, const RobotTask& task, const View& v, std::string_view color) {
  const double eps = std::max(0.0, task.controller.params.epsilon) * v.scale;
  const std::string_view fill = color.empty() ? std::string_view(kGoalFill) : color;
  const std::string_view stroke = color.empty() ? std::string_view(kGoalStroke) : color;
  for (const Vec2& g : task.goals) {
    if (!is_finite(g)) continue;
    fmt::format_to(out,
                   R"(<circle cx="{}" cy="{}" r="{}" fill="{}" fill-opacity="0.18" stroke="{}" )"
                   R"(stroke-width="1.2" stroke-dasharray="4 3"/>)"
                   "\n",
                   Px{v.x(g.x())}, Px{v.y(g.y())}, Px{std::max(eps, 3.0)}, fill, stroke);
  }
}

void draw_goal_flags(SvgOut out, const RobotTask& task, const View& v, std::string_view color,
                     bool numbered) {
  const std::string_view fill = color.empty() ? std::string_view(kGoalFill) : color;
  const std::string_view stroke = color.empty() ? std::string_view(kGoalStroke) : color;
  const std::string_view text = color.empty() ? std::string_view("#5c4800") : color;
  for (std::size_t i = 0; i < task.goals.size(); ++i) {
    const Vec2& g = task.goals[i];
    if (!is_finite(g)) continue;
    draw_flag(out, v.x(g.x()), v.y(g.y()), 13.0, fill, stroke);
    if (numbered)
      fmt::format_to(out,
                     R"(<text class="goal-number" x="{}" y="{}" font-family="{}" font-size="11" )"
                     R"(font-weight="bold" fill="{}" stroke="#ffffff" stroke-width="2.5" )"
                     R"(paint-order="stroke">{}</text>)"
                     "\n",
                     Px{v.x(g.x()) + 15}, Px{v.y(g.y()) - 12}, kFont, text, i + 1);
  }
}

}  // namespace floornav::render_detail
