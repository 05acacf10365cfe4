#include "floornav/render/trajectory_svg.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "legend.hpp"
#include "picture_layout.hpp"
#include "run_caption.hpp"
#include "run_drawing.hpp"
#include "svg_text.hpp"
#include "world_drawing.hpp"

namespace floornav {

namespace {

using namespace render_detail;

constexpr double kMapMaxWidth = 860.0;    ///< px available to the world's width
constexpr double kMapMaxHeight = 1000.0;  ///< px available to the world's height
constexpr double kPad = 20.0;             ///< px around everything
constexpr double kTitleHeight = 58.0;     ///< px for the title and the subtitle
constexpr double kMinCanvasWidth = 640.0;
constexpr double kScaleBarRoom = 190.0;  ///< px kept free at the right of the legend
constexpr std::size_t kMaxPathPoints = 5000;
/// Fleets up to this size have each robot named beside its start.
constexpr std::size_t kMaxNamedRobots = 40;

/// The picture of one or more robots in one world: `title` and `numbers` are the two lines of
/// text at the top.
std::string render_tracks(const Scenario& scenario, std::span<const Track> tracks,
                          const std::string& title, const std::string& numbers) {
  const World* world = scenario.world.get();
  const OccupancyGrid* grid = world ? world->grid() : nullptr;
  View v = fit_view(picture_extent(world, tracks), kMapMaxWidth, kMapMaxHeight);
  const double canvas_w = std::max(v.width + 2 * (kPad + kMapMargin), kMinCanvasWidth);
  v.left = 0.5 * (canvas_w - v.width);
  v.top = kTitleHeight + kMapMargin;

  const std::vector<LegendItem> items = legend_items(tracks, grid && grid->has_unknown());
  const auto rows = legend_rows(items, canvas_w - 2 * kPad - kScaleBarRoom);
  const double legend_top = v.top + v.height + kMapMargin + 12.0;
  const double canvas_h = legend_top + static_cast<double>(rows.size()) * kLegendRow + kPad;
  bool any_collided = false;
  for (const Track& t : tracks) any_collided = any_collided || t.run->collided;
  // Path points are shared among the robots, so that a big fleet's picture stays small.
  const std::size_t max_points =
      std::max<std::size_t>(kMaxPathPoints / std::max<std::size_t>(tracks.size(), 1), 50);
  const bool fleet = tracks.size() > 1;

  fmt::memory_buffer buf;
  buf.reserve(64 * 1024);
  SvgOut out(buf);
  fmt::format_to(out,
                 R"(<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" )"
                 R"(viewBox="0 0 {} {}">)"
                 "\n",
                 Px{canvas_w}, Px{canvas_h}, Px{canvas_w}, Px{canvas_h});
  fmt::format_to(out, "<title>{}</title>\n", Xml{scenario.name});

  draw_background(out, world, v, canvas_w, canvas_h);
  if (grid) draw_grid(out, *grid, v);
  if (world) draw_obstacles(out, *world, v);
  if (world) draw_walls(out, *world, v);
  for (const Track& t : tracks) draw_goal_areas(out, *t.task, v, t.color);
  for (const Track& t : tracks) draw_path(out, t, v, max_points);
  for (const Track& t : tracks) draw_switches(out, *t.run, v);

  for (const Track& t : tracks) {
    const RobotTask& task = *t.task;
    const RunResult& r = *t.run;
    const std::string_view start_stroke = fleet ? std::string_view(t.color) : "#333333";
    draw_body(out, task.robot, task.start.position.x(), task.start.position.y(), task.start.theta,
              v, "#ffffff", 0.85, start_stroke);
    if (r.collided)
      draw_body(out, task.robot, r.final_x, r.final_y, r.final_theta, v, "#d62728", 0.85,
                "#7f0000");
    else if (fleet)
      draw_body(out, task.robot, r.final_x, r.final_y, r.final_theta, v, t.color, 0.75, "#263238");
    else
      draw_body(out, task.robot, r.final_x, r.final_y, r.final_theta, v, "#90a4ae", 0.9, "#263238");
  }
  // Over the final bodies; a fleet's goals are numbered in each robot's route order.
  for (const Track& t : tracks)
    draw_goal_flags(out, *t.task, v, t.color, fleet || t.task->goals.size() > 1);
  // A small fleet's robots are named at their start.
  if (fleet && tracks.size() <= kMaxNamedRobots)
    for (const Track& t : tracks) {
      const RobotTask& task = *t.task;
      const double body_px = std::max(body_reach(task.robot) * v.scale, kMinRobotRadius);
      fmt::format_to(out,
                     R"(<text x="{}" y="{}" font-family="{}" font-size="11" fill="{}" )"
                     R"(text-anchor="middle">{}</text>)"
                     "\n",
                     Px{v.x(task.start.position.x())},
                     Px{v.y(task.start.position.y()) - body_px - 4}, kFont, t.color,
                     Xml{t.run->scenario});
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
  draw_legend(out, rows, any_collided, kPad, legend_top);
  draw_scale_bar(out, canvas_w - kPad, legend_top + 0.5 * kLegendRow, v.scale);
  fmt::format_to(out, "</svg>\n");
  return fmt::to_string(buf);
}

}  // namespace

std::string render_trajectory_svg(const Scenario& s, const RunResult& r) {
  const Caption c = run_caption(s, r);
  const Track track{&s.robot(), &r, ""};
  return render_tracks(s, std::span<const Track>(&track, 1), c.title, c.numbers);
}

std::string render_fleet_svg(const Scenario& s, const FleetResult& f) {
  std::vector<Track> tracks;
  for (std::size_t i = 0; i < f.robots.size() && i < s.robots.size(); ++i)
    tracks.push_back({&s.robots[i], &f.robots[i], robot_color(i)});
  // A fleet of one is drawn like a lone robot: its path coloured by mode.
  if (tracks.size() == 1) tracks.front().color.clear();
  const Caption c = fleet_caption(s, f);
  return render_tracks(s, tracks, c.title, c.numbers);
}

}  // namespace floornav
