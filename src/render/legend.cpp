#include "legend.hpp"

#include <algorithm>

#include "floornav/render/palette.hpp"
#include "run_drawing.hpp"

namespace floornav::render_detail {

namespace {

constexpr double kIconWidth = 24.0;

std::string mode_label(const RunResult& r, int mode) {
  if (mode >= 0 && static_cast<std::size_t>(mode) < r.mode_names.size())
    return r.mode_names[static_cast<std::size_t>(mode)];
  return "mode_" + std::to_string(mode);
}

double item_width(const LegendItem& item) {
  return kIconWidth + 6.0 + text_width(item.label, kLegendFont) + 18.0;
}

/// The modes a run spent time in (or passed through), named ones in mode order, then the others.
std::vector<int> modes_that_ran(const RunResult& r) {
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
  std::vector<int> modes;
  for (int m = 0; m < n; ++m)
    if (used[static_cast<std::size_t>(m)]) modes.push_back(m);
  modes.insert(modes.end(), extra.begin(), extra.end());
  return modes;
}

}  // namespace

std::vector<LegendItem> legend_items(std::span<const Track> tracks, bool unknown_cells) {
  std::vector<LegendItem> items;
  const bool fleet = tracks.size() > 1;
  bool goals = false, many_goals = false, switches = false, collided = false;
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    const Track& t = tracks[i];
    const RunResult& r = *t.run;
    if (fleet) {
      if (i < kMaxLegendRobots)
        items.push_back({LegendIcon::Line, r.scenario, t.color});
      else if (i == kMaxLegendRobots)
        items.push_back({LegendIcon::Line, fmt::format("+ {} more", tracks.size() - i), "#999999"});
    } else {
      for (int m : modes_that_ran(r)) {
        std::string label = mode_label(r, m);
        if (std::none_of(items.begin(), items.end(),
                         [&](const LegendItem& it) { return it.label == label; }))
          items.push_back(
              {LegendIcon::Line, std::move(label), std::string(mode_color_of(r.mode_names, m))});
      }
    }
    goals = goals || !t.task->goals.empty();
    many_goals = many_goals || t.task->goals.size() > 1 || (goals && fleet);
    switches = switches || !r.transition_x.empty();
    collided = collided || r.collided;
  }
  items.push_back({LegendIcon::Start, "start", ""});
  if (goals) items.push_back({LegendIcon::Goal, many_goals ? "goals" : "goal", ""});
  if (switches) items.push_back({LegendIcon::Switch, "mode switch", ""});
  items.push_back({LegendIcon::End, collided ? "end (collision)" : "end", ""});
  if (unknown_cells) items.push_back({LegendIcon::Unknown, "unknown (map)", ""});
  return items;
}

std::vector<std::vector<const LegendItem*>> legend_rows(const std::vector<LegendItem>& items,
                                                        double width) {
  std::vector<std::vector<const LegendItem*>> rows(1);
  double used = 0.0;
  for (const LegendItem& item : items) {
    const double w = item_width(item);
    if (!rows.back().empty() && used + w > width) {
      rows.emplace_back();
      used = 0.0;
    }
    rows.back().push_back(&item);
    used += w;
  }
  return rows;
}

namespace {

void draw_icon(SvgOut out, const LegendItem& item, bool collided, double x, double cy) {
  switch (item.icon) {
    case LegendIcon::Line:
      fmt::format_to(out,
                     R"(<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{}" stroke-width="4" )"
                     R"(stroke-linecap="round"/>)"
                     "\n",
                     Px{x + 2}, Px{cy}, Px{x + kIconWidth - 2}, Px{cy}, item.color);
      break;
    case LegendIcon::Start:
      draw_disc_robot(out, x + kIconWidth / 2, cy, 6.5, 0.0, "#ffffff", 1.0, "#333333");
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
        draw_disc_robot(out, x + kIconWidth / 2, cy, 6.5, 0.0, "#d62728", 0.85, "#7f0000");
      else
        draw_disc_robot(out, x + kIconWidth / 2, cy, 6.5, 0.0, "#90a4ae", 0.9, "#263238");
      break;
    case LegendIcon::Unknown:
      fmt::format_to(
          out,
          R"svg(<rect x="{}" y="{}" width="{}" height="12" fill="url(#unknown-cells)" )svg"
          R"(stroke="#9a96a8"/>)"
          "\n",
          Px{x + 3}, Px{cy - 6}, Px{kIconWidth - 6});
      break;
  }
}

}  // namespace

void draw_legend(SvgOut out, const std::vector<std::vector<const LegendItem*>>& rows, bool collided,
                 double left, double top) {
  for (std::size_t row = 0; row < rows.size(); ++row) {
    const double cy = top + kLegendRow * (static_cast<double>(row) + 0.5);
    double x = left;
    for (const LegendItem* item : rows[row]) {
      draw_icon(out, *item, collided, x, cy);
      fmt::format_to(out,
                     R"(<text x="{}" y="{}" font-family="{}" font-size="{}" fill="#333333">{})"
                     R"(</text>)"
                     "\n",
                     Px{x + kIconWidth + 6}, Px{cy + 4}, kFont, kLegendFont, Xml{item->label});
      x += item_width(*item);
    }
  }
}

void draw_scale_bar(SvgOut out, double right, double cy, double px_per_m) {
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

}  // namespace floornav::render_detail
