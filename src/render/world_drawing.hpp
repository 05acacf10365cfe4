#pragma once
/// @file
/// Private to the render module: the world in an SVG picture. The floor inside the bounds is
/// white and outside light grey; walls are drawn outside the bounds, so that their inner edge is
/// where a robot collides; map cells are grey when occupied and hatched when unknown.

#include "floornav/world/occupancy_grid.hpp"
#include "floornav/world/world.hpp"
#include "picture_layout.hpp"
#include "svg_text.hpp"

namespace floornav::render_detail {

inline constexpr double kMapMargin = 22.0;  ///< px between the world's extent and the map frame

/// The canvas and the map frame (`world` may be null: an empty floor).
void draw_background(SvgOut out, const World* world, const View& v, double canvas_w,
                     double canvas_h);
/// The grid's occupied cells as one path (one rectangle per horizontal run, in cell units under
/// a transform) and its unknown cells as a second, hatched one. Grids over 4 million cells are
/// drawn in k x k blocks: occupied when any cell is, else unknown when any cell is.
void draw_grid(SvgOut out, const OccupancyGrid& grid, const View& v);
void draw_obstacles(SvgOut out, const World& world, const View& v);
void draw_walls(SvgOut out, const World& world, const View& v);

}  // namespace floornav::render_detail
