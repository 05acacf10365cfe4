#pragma once
// The progress bar of `floornav batch` and `sweep` on a terminal's stderr.

#include "floornav/runner/batch.hpp"

namespace floornav::app {

/// Draws `[#####.....] done/total  rate runs/s  ETA s` over the previous bar (a carriage return,
/// no newline); the batch's last report ends the line. For BatchOptions::progress.
void draw_progress_bar(const BatchProgress& progress);

}  // namespace floornav::app
