#include "progress_bar.hpp"

#include <cstdio>
#include <string>

namespace floornav::app {

void draw_progress_bar(const BatchProgress& p) {
  if (p.finished) {
    std::fputs("\n", stderr);
    return;
  }
  const double rate = p.elapsed > 0 ? static_cast<double>(p.done) / p.elapsed : 0.0;
  const double eta = rate > 0 ? static_cast<double>(p.total - p.done) / rate : 0.0;
  constexpr int kWidth = 30;
  const int filled = p.total ? static_cast<int>(kWidth * p.done / p.total) : kWidth;
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r[%s] %zu/%zu  %.1f runs/s  ETA %.0f s ", bar.c_str(), p.done, p.total,
               rate, eta);
  std::fflush(stderr);
}

}  // namespace floornav::app
