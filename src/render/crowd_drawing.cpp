#include "crowd_drawing.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "floornav/geometry/oriented_box.hpp"

namespace floornav::render_detail {

namespace {

constexpr const char* kPersonColor = "#7b3fa0";
constexpr const char* kForkliftColor = "#b35900";
constexpr std::size_t kMaxCrowdPathPoints = 500;  ///< per person or forklift

void draw_crowd_path(SvgOut out, const CrowdTrack& t, const View& v, const char* color,
                     const char* extra) {
  if (t.samples.size() < 2) return;
  const std::size_t every = std::max<std::size_t>(1, t.samples.size() / kMaxCrowdPathPoints);
  fmt::format_to(out,
                 R"(<polyline fill="none" stroke="{}" stroke-width="1.2" )"
                 R"(stroke-opacity="0.55" {}points=")",
                 color, extra);
  for (std::size_t k = 0; k < t.samples.size(); k += every)
    fmt::format_to(out, "{},{} ", Px{v.x(t.samples[k].x)}, Px{v.y(t.samples[k].y)});
  fmt::format_to(out, "{},{}\"/>\n", Px{v.x(t.samples.back().x)}, Px{v.y(t.samples.back().y)});
}

}  // namespace

void draw_crowd(SvgOut out, const CrowdResult& c, const View& v) {
  for (const CrowdTrack& t : c.forklifts)
    draw_crowd_path(out, t, v, kForkliftColor, R"(stroke-dasharray="6 4" )");
  for (const CrowdTrack& t : c.people) draw_crowd_path(out, t, v, kPersonColor, "");
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

}  // namespace floornav::render_detail
