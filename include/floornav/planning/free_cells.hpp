#pragma once
/// @file
/// The configuration space of a disc robot on a raster: which cells of a RasterFrame a robot of a
/// given radius may stand on.

#include "floornav/geometry/pose2.hpp"
#include "floornav/planning/free_raster.hpp"
#include "floornav/planning/raster_frame.hpp"

namespace floornav {

class World;

/// The configuration space of a disc robot on a raster: cell (ix, iy), covering
/// [ix, ix + 1) x [iy, iy + 1) times `cell` in the frame `origin`, is free when
/// `world.clearance` at its centre exceeds `body_radius`. Empty for a non-positive size.
FreeRaster free_cells(const World& world, double body_radius, const Pose2& origin, double cell,
                      int width, int height);

/// `free_cells` over `frame`.
FreeRaster free_cells(const World& world, double body_radius, const RasterFrame& frame);

/// `free_cells` over `frame` (of a positive size) into `out`, whose memory is reused (a batch
/// builds one raster per world).
void free_cells_into(const World& world, double body_radius, const RasterFrame& frame,
                     FreeRaster& out);

}  // namespace floornav
