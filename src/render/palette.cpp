#include "floornav/render/palette.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <utility>

namespace floornav {

namespace {

constexpr std::array<std::pair<std::string_view, std::string_view>, 6> kModeColors{{
    {"go_to_goal", "#1f77b4"},
    {"follow_boundary_cw", "#ff7f0e"},
    {"follow_boundary_ccw", "#2ca02c"},
    {"avoid_obstacle", "#d62728"},
    {"blended", "#9467bd"},
    {"stop", "#000000"},
}};
constexpr std::array<std::string_view, 5> kSpareColors{"#8c564b", "#e377c2", "#17becf", "#bcbd22",
                                                       "#7f7f7f"};
constexpr std::array<std::string_view, 8> kRobotColors{"#1b9e77", "#d95f02", "#7570b3", "#e7298a",
                                                       "#66a61e", "#e6ab02", "#a6761d", "#666666"};

bool has_named_color(std::string_view name) {
  return std::any_of(kModeColors.begin(), kModeColors.end(),
                     [&](const auto& kc) { return kc.first == name; });
}

}  // namespace

std::string_view mode_color(std::string_view name, int fallback_index) {
  for (const auto& [mode, color] : kModeColors)
    if (mode == name) return color;
  return kSpareColors[static_cast<std::size_t>(std::abs(fallback_index)) % kSpareColors.size()];
}

std::string_view mode_color_of(std::span<const std::string> mode_names, int mode) {
  int spare = 0;
  for (int m = 0; m < static_cast<int>(mode_names.size()); ++m) {
    const std::string& name = mode_names[static_cast<std::size_t>(m)];
    if (m == mode) return mode_color(name, spare);
    if (!has_named_color(name)) ++spare;
  }
  return kSpareColors[static_cast<std::size_t>(std::abs(mode)) % kSpareColors.size()];
}

std::string robot_color(std::size_t index) {
  if (index < kRobotColors.size()) return std::string(kRobotColors[index]);
  // HSL(h, 65 %, 42 %) with h stepping by the golden angle: dark enough for white labels.
  const double h = std::fmod(static_cast<double>(index - kRobotColors.size()) * 137.50776, 360.0);
  const double s = 0.65, l = 0.42;
  const double c = (1.0 - std::abs(2.0 * l - 1.0)) * s;
  const double x = c * (1.0 - std::abs(std::fmod(h / 60.0, 2.0) - 1.0));
  const double m = l - c / 2.0;
  double r = 0, g = 0, b = 0;
  if (h < 60)
    r = c, g = x;
  else if (h < 120)
    r = x, g = c;
  else if (h < 180)
    g = c, b = x;
  else if (h < 240)
    g = x, b = c;
  else if (h < 300)
    r = x, b = c;
  else
    r = c, b = x;
  auto byte = [&](double v) { return static_cast<int>(std::lround((v + m) * 255.0)); };
  return fmt::format("#{:02x}{:02x}{:02x}", byte(r), byte(g), byte(b));
}

}  // namespace floornav
