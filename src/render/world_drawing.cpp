#include "world_drawing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace floornav::render_detail {

namespace {

constexpr std::int64_t kMaxGridCells = 4'000'000;
constexpr const char* kObstacleFill = "#c9ccd1";
constexpr const char* kObstacleStroke = "#6b7079";
constexpr const char* kGridFill = "#a9adb3";
constexpr const char* kUnknownFill = "#e4e0f0";  ///< lilac under grey hatching: not an obstacle
constexpr const char* kWall = "#37474f";

enum Cell : std::uint8_t { kFree = 0, kUnknown = 1, kOccupied = 2 };

/// One path of rectangles, one per horizontal run of cells equal to `which` in `cells` (w x h).
void draw_runs(SvgOut out, const std::vector<std::uint8_t>& cells, int w, int h,
               std::uint8_t which) {
  for (int iy = 0; iy < h; ++iy) {
    const std::uint8_t* row =
        cells.data() + static_cast<std::size_t>(iy) * static_cast<std::size_t>(w);
    for (int ix = 0; ix < w;) {
      if (row[ix] != which) {
        ++ix;
        continue;
      }
      int end = ix;
      while (end < w && row[end] == which) ++end;
      fmt::format_to(out, "M{} {}h{}v1h-{}z", ix, iy, end - ix, end - ix);
      ix = end;
    }
  }
}

}  // namespace

void draw_background(SvgOut out, const World* world, const View& v, double canvas_w,
                     double canvas_h) {
  fmt::format_to(out,
                 R"(<rect width="{}" height="{}" fill="#ffffff"/>)"
                 "\n",
                 Px{canvas_w}, Px{canvas_h});
  const double fx = v.left - kMapMargin;
  const double fy = v.top - kMapMargin;
  const double fw = v.width + 2 * kMapMargin;
  const double fh = v.height + 2 * kMapMargin;
  const bool bounded = world && world->bounds();
  // Outside the bounds is solid: a light grey, so the free floor stands out.
  fmt::format_to(out,
                 R"(<rect x="{}" y="{}" width="{}" height="{}" fill="{}" stroke="#d5d8dc"/>)"
                 "\n",
                 Px{fx}, Px{fy}, Px{fw}, Px{fh}, bounded ? "#eceef0" : "#fdfdfd");
  if (bounded) {
    const Box2& b = *world->bounds();
    fmt::format_to(out,
                   R"(<rect x="{}" y="{}" width="{}" height="{}" fill="#ffffff"/>)"
                   "\n",
                   Px{v.x(b.min.x())}, Px{v.y(b.max.y())}, Px{b.size().x() * v.scale},
                   Px{b.size().y() * v.scale});
  }
}

void draw_walls(SvgOut out, const World& world, const View& v) {
  if (!world.bounds()) return;
  const Box2& b = *world.bounds();
  // The wall is drawn outside the bounds, so that its inner edge is where the robot collides.
  const double t = std::clamp(0.03 * v.scale, 4.0, 10.0);
  fmt::format_to(out,
                 R"(<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="{}" )"
                 R"(stroke-width="{}" stroke-linejoin="miter"/>)"
                 "\n",
                 Px{v.x(b.min.x()) - t / 2}, Px{v.y(b.max.y()) - t / 2},
                 Px{b.size().x() * v.scale + t}, Px{b.size().y() * v.scale + t}, kWall, Px{t});
}

void draw_grid(SvgOut out, const OccupancyGrid& g, const View& v) {
  const std::int64_t cells = static_cast<std::int64_t>(g.width()) * g.height();
  if (cells <= 0 || (g.occupied_count() == 0 && !g.has_unknown())) return;
  int k = 1;
  while ((static_cast<std::int64_t>(g.width() + k - 1) / k) *
             ((static_cast<std::int64_t>(g.height()) + k - 1) / k) >
         kMaxGridCells)
    ++k;
  const int w = (g.width() + k - 1) / k;
  const int h = (g.height() + k - 1) / k;
  std::vector<std::uint8_t> block(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), kFree);
  bool any_unknown = false;
  for (int iy = 0; iy < g.height(); ++iy)
    for (int ix = 0; ix < g.width(); ++ix) {
      // An unknown cell is drawn as unknown, whatever the loader's policy made of it.
      const std::uint8_t c = g.unknown(ix, iy) ? kUnknown : g.occupied(ix, iy) ? kOccupied : kFree;
      std::uint8_t& b = block[static_cast<std::size_t>(iy / k) * static_cast<std::size_t>(w) +
                              static_cast<std::size_t>(ix / k)];
      b = std::max(b, c);
      any_unknown = any_unknown || c == kUnknown;
    }

  // Cell (u, v) -> world origin + R(yaw) (u, v) res k -> pixels (y flipped).
  const double cell = g.resolution() * k * v.scale;
  const double c = std::cos(g.origin().theta);
  const double s = std::sin(g.origin().theta);
  const Vec2& o = g.origin().position;
  const auto transform = fmt::format("matrix({:.6g} {:.6g} {:.6g} {:.6g} {:.6g} {:.6g})", cell * c,
                                     -cell * s, -cell * s, -cell * c, v.x(o.x()), v.y(o.y()));
  if (any_unknown || g.has_unknown()) {
    // Unknown cells: a pale fill with grey hatching, so they read as "not mapped", not as walls.
    fmt::format_to(out,
                   R"(<defs><pattern id="unknown-cells" width="6" height="6" )"
                   R"svg(patternUnits="userSpaceOnUse" patternTransform="rotate(45)">)svg"
                   R"(<rect width="6" height="6" fill="{}"/>)"
                   R"(<line x1="0" y1="0" x2="0" y2="6" stroke="#9a96a8" stroke-width="1.2"/>)"
                   "</pattern></defs>\n",
                   kUnknownFill);
    fmt::format_to(out,
                   R"svg(<path class="unknown" fill="url(#unknown-cells)" transform="{}" d=")svg",
                   transform);
    draw_runs(out, block, w, h, kUnknown);
    fmt::format_to(out, "\"/>\n");
  }
  fmt::format_to(out, R"svg(<path class="occupied" fill="{}" transform="{}" d=")svg", kGridFill,
                 transform);
  draw_runs(out, block, w, h, kOccupied);
  fmt::format_to(out, "\"/>\n");
}

void draw_obstacles(SvgOut out, const World& w, const View& v) {
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

}  // namespace floornav::render_detail
