#pragma once
/// @file
/// Private to the render module: people and forklifts in a fleet's picture. People's paths are
/// thin purple lines with their bodies where they ended; forklifts' paths are brown and dashed,
/// with their footprints where they ended. They are drawn under the robots.

#include "floornav/sim/crowd.hpp"
#include "picture_layout.hpp"
#include "svg_text.hpp"

namespace floornav::render_detail {

void draw_crowd(SvgOut out, const CrowdResult& crowd, const View& v);

}  // namespace floornav::render_detail
