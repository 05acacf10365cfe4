#pragma once
/// @file
/// The colours of the pictures (SVG and HTML replay alike): one per navigation mode, one per
/// robot of a fleet. `#rrggbb` strings.

#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace floornav {

/// Colour used for the mode called `name`: go_to_goal blue, follow_boundary_cw orange,
/// follow_boundary_ccw green, avoid_obstacle red, blended purple, stop black; other names get the
/// `fallback_index`-th colour of a spare palette.
std::string_view mode_color(std::string_view name, int fallback_index = 0);

/// Colour of mode `mode` of a controller whose modes are `mode_names`: mode_color of its name,
/// the unknown names taking the spare colours in order; a mode without a name gets a spare one.
std::string_view mode_color_of(std::span<const std::string> mode_names, int mode);

/// Colour of robot `index` of a fleet: eight well-separated colours (ColorBrewer Dark2), then
/// hues a golden angle apart, so that neighbours in the list never look alike.
std::string robot_color(std::size_t index);

}  // namespace floornav
