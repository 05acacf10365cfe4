#pragma once
/// @file
/// Private to the render module: which trajectory rows the HTML replay keeps. The page
/// interpolates linearly in time between kept rows (positions, and headings the short way
/// round), so a row may be dropped only while that interpolation stays within tolerance of it.

#include <cstddef>
#include <span>
#include <vector>

#include "floornav/sim/run_result.hpp"

namespace floornav::render_detail {

struct TrackTolerance {
  double position{0.009};  ///< m: interpolated positions within this of every row (the page
                           ///< stores millimetres: 0.009 + 0.0007 stays under 1 cm)
  double heading{0.01};    ///< rad
};

/// Indices of the rows to keep, increasing, always the first and the last: a Douglas-Peucker
/// split in time (a row is kept where the interpolation between the kept neighbours misses it
/// most, until none misses by more than the tolerance), over chunks of at most 4096 rows so
/// that the cost stays O(rows x log) even for pathological paths. Non-finite rows are kept.
std::vector<std::size_t> decimate_track(std::span<const TrajectorySample> rows,
                                        const TrackTolerance& tolerance = {});

}  // namespace floornav::render_detail
