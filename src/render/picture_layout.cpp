#include "picture_layout.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "floornav/world/occupancy_grid.hpp"

namespace floornav::render_detail {

void Extent::add(double x, double y, double pad) {
  if (!std::isfinite(x) || !std::isfinite(y)) return;
  xmin = std::min(xmin, x - pad);
  ymin = std::min(ymin, y - pad);
  xmax = std::max(xmax, x + pad);
  ymax = std::max(ymax, y + pad);
}

double body_reach(const RobotSpec& robot) {
  double reach = std::max(0.0, robot.body_radius);
  for (const Vec2& v : robot.footprint)
    if (is_finite(v)) reach = std::max(reach, v.norm());
  return reach;
}

bool world_has_content(const World& w) {
  return w.bounds() || !w.circles().empty() || !w.polygons().empty() || w.grid() != nullptr;
}

namespace {

void add_grid_extent(Extent& e, const OccupancyGrid& g) {
  const double w = g.width() * g.resolution();
  const double h = g.height() * g.resolution();
  for (const Vec2& corner : {Vec2(0, 0), Vec2(w, 0), Vec2(0, h), Vec2(w, h)}) {
    const Vec2 p = g.origin().transform_point(corner);
    e.add(p.x(), p.y());
  }
}

}  // namespace

Extent picture_extent(const World* world, std::span<const Track> tracks) {
  Extent e;
  if (world && world_has_content(*world)) {
    const Box2& box = world->extent();
    e.add(box.min.x(), box.min.y());
    e.add(box.max.x(), box.max.y());
    if (const OccupancyGrid* g = world->grid()) add_grid_extent(e, *g);
  }
  double body = 0.0;
  for (const Track& t : tracks) {
    const RobotTask& task = *t.task;
    const RunResult& r = *t.run;
    const double b = body_reach(task.robot);
    body = std::max(body, b);
    e.add(task.start.position.x(), task.start.position.y(), b);
    for (const Vec2& goal : task.goals)
      e.add(goal.x(), goal.y(), std::max(0.0, task.controller.params.epsilon));
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

View fit_view(const Extent& e, double max_width, double max_height) {
  const double w_m = e.xmax - e.xmin;
  const double h_m = e.ymax - e.ymin;
  View v;
  v.scale = std::min(max_width / w_m, max_height / h_m);
  v.width = w_m * v.scale;
  v.height = h_m * v.scale;
  v.xmin = e.xmin;
  v.ymax = e.ymax;
  return v;
}

double scale_bar_length(double px_per_m) {
  double best = 0.0;
  for (int e = -4; e <= 6; ++e)
    for (double m : {1.0, 2.0, 5.0}) {
      const double len = m * std::pow(10.0, e);
      if (len * px_per_m <= 160.0) best = len;
    }
  return best > 0.0 ? best : 1e-4;
}

double text_width(std::string_view text, double font_size) {
  return 0.58 * font_size * static_cast<double>(text.size());
}

}  // namespace floornav::render_detail
