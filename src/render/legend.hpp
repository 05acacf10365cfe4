#pragma once
/// @file
/// Private to the render module: the legend under an SVG picture (what each colour and marker
/// means, laid out in rows that fit the canvas) and the scale bar at its right.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "picture_layout.hpp"
#include "svg_text.hpp"

namespace floornav::render_detail {

inline constexpr double kLegendFont = 12.0;
inline constexpr double kLegendRow = 22.0;
/// A fleet's legend names this many robots at most, then "+ N more".
inline constexpr std::size_t kMaxLegendRobots = 24;

enum class LegendIcon { Line, Start, Goal, Switch, End, Unknown };

struct LegendItem {
  LegendIcon icon;
  std::string label;
  std::string color;  ///< the line's colour (LegendIcon::Line)
};

/// A lone robot: the modes that ran, in mode order, each in its colour. A fleet: every robot's
/// name in its colour. Then start, goal(s), mode switch, end; "unknown (map)" when the map has
/// unknown cells.
std::vector<LegendItem> legend_items(std::span<const Track> tracks, bool unknown_cells);

/// Rows of legend items that fit in `width` px.
std::vector<std::vector<const LegendItem*>> legend_rows(const std::vector<LegendItem>& items,
                                                        double width);

/// Draws the rows from (`left`, `top`) down, `kLegendRow` px apart.
void draw_legend(SvgOut out, const std::vector<std::vector<const LegendItem*>>& rows, bool collided,
                 double left, double top);

/// A bar of a round length (scale_bar_length) ending at `right`, centred on `cy`, labelled.
void draw_scale_bar(SvgOut out, double right, double cy, double px_per_m);

}  // namespace floornav::render_detail
