#include "floornav/render/frame_raster.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace floornav {

namespace {
// trajectory.svg's colours (world_drawing.cpp, crowd_drawing.cpp).
constexpr Rgb kFloor{255, 255, 255};
constexpr Rgb kObstacle{201, 204, 209};  // #c9ccd1
constexpr Rgb kEdge{107, 112, 121};      // #6b7079
constexpr Rgb kPerson{123, 63, 160};     // #7b3fa0
constexpr Rgb kForklift{179, 89, 0};     // #b35900
constexpr Rgb kHeading{20, 20, 20};

Rgb darker(Rgb c) {
  return {static_cast<std::uint8_t>(c.r * 3 / 5), static_cast<std::uint8_t>(c.g * 3 / 5),
          static_cast<std::uint8_t>(c.b * 3 / 5)};
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}
}  // namespace

Rgb rgb_of(std::string_view hex) {
  if (hex.size() != 7 || hex[0] != '#') return {};
  std::array<std::uint8_t, 3> v{};
  for (std::size_t k = 0; k < 3; ++k) {
    const int hi = hex_digit(hex[1 + 2 * k]), lo = hex_digit(hex[2 + 2 * k]);
    if (hi < 0 || lo < 0) return {};
    v[k] = static_cast<std::uint8_t>(16 * hi + lo);
  }
  return {v[0], v[1], v[2]};
}

FrameRaster::FrameRaster(const World& world, int height, int width, std::optional<Box2> area)
    : height_(height), width_(width) {
  if (height < 8 || width < 8 || height > 8192 || width > 8192)
    throw std::invalid_argument("a frame is 8 to 8192 pixels on each side");
  Box2 box = area ? *area : world.bounds() ? *world.bounds() : world.extent();
  if (!area) {  // a margin, so that the walls show
    Vec2 size = box.size();
    if (size.x() <= 0.0 && size.y() <= 0.0) size = Vec2(10.0, 10.0);
    const double m = 0.03 * std::max(size.x(), size.y());
    box.min -= Vec2(m, m);
    box.max += Vec2(m, m);
  }
  const Vec2 size = box.size().cwiseMax(Vec2(1e-6, 1e-6));
  scale_ = std::min(width / size.x(), height / size.y());
  const Vec2 centre = 0.5 * (box.min + box.max);
  left_ = centre.x() - 0.5 * width / scale_;
  top_ = centre.y() + 0.5 * height / scale_;

  background_.assign(3 * static_cast<std::size_t>(width) * height, 255);
  const std::span<std::uint8_t> bg(background_);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Vec2 p(left_ + (x + 0.5) / scale_, top_ - (y + 0.5) / scale_);
      put(bg, x, y, world.is_inside_obstacle(p) ? kObstacle : kFloor);
    }
  for (const Segment& s : world.segments()) line(bg, to_pixel(s.a), to_pixel(s.b), kEdge);
  if (const auto& b = world.bounds()) {
    const std::array<Vec2, 4> c{b->min, Vec2(b->max.x(), b->min.y()), b->max,
                                Vec2(b->min.x(), b->max.y())};
    for (std::size_t k = 0; k < 4; ++k) line(bg, to_pixel(c[k]), to_pixel(c[(k + 1) % 4]), kEdge);
  }
}

void FrameRaster::draw(std::span<std::uint8_t> rgb, std::span<const FrameRobot> robots,
                       std::span<const Circle> people,
                       std::span<const OrientedBox> forklifts) const {
  if (rgb.size() != background_.size())
    throw std::invalid_argument("a frame buffer of the wrong size");
  std::memcpy(rgb.data(), background_.data(), background_.size());
  for (const Circle& c : people) disc(rgb, to_pixel(c.center), c.radius * scale_, kPerson);
  for (const OrientedBox& b : forklifts) {
    std::array<Vec2, 4> px;
    const auto corners = b.corners();
    for (std::size_t k = 0; k < 4; ++k) px[k] = to_pixel(corners[k]);
    polygon(rgb, px, kForklift);
  }
  for (const FrameRobot& r : robots) {
    if (r.goal) {  // a cross of about 1.5 body radii, at least 3 pixels
      const Vec2 g = to_pixel(*r.goal);
      const double h = std::max(3.0, 1.5 * r.radius * scale_);
      line(rgb, g - Vec2(h, h), g + Vec2(h, h), r.colour);
      line(rgb, g - Vec2(h, -h), g + Vec2(h, -h), r.colour);
    }
    const Rgb dots = darker(r.colour);
    for (const Vec2& p : r.returns) dot(rgb, to_pixel(p), dots);
    const Vec2 c = to_pixel(r.pose.position);
    const Vec2 heading(std::cos(r.pose.theta), std::sin(r.pose.theta));
    if (r.footprint.empty()) {
      disc(rgb, c, std::max(1.0, r.radius * scale_), r.colour);
    } else {
      std::array<Vec2, 16> px;
      const std::size_t n = std::min(r.footprint.size(), px.size());
      for (std::size_t k = 0; k < n; ++k) {
        const Vec2& v = r.footprint[k];
        const Vec2 w(heading.x() * v.x() - heading.y() * v.y(),
                     heading.y() * v.x() + heading.x() * v.y());
        px[k] = to_pixel(r.pose.position + w);
      }
      polygon(rgb, std::span<const Vec2>(px.data(), n), r.colour);
    }
    line(rgb, c, to_pixel(r.pose.position + r.radius * heading), kHeading);
  }
}

void FrameRaster::disc(std::span<std::uint8_t> rgb, const Vec2& c, double r, Rgb fill) const {
  const int y0 = std::max(0, static_cast<int>(std::floor(c.y() - r)));
  const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(c.y() + r)));
  for (int y = y0; y <= y1; ++y) {
    const double dy = y + 0.5 - c.y();
    const double w2 = r * r - dy * dy;
    if (w2 < 0.0) continue;
    const double w = std::sqrt(w2);
    const int x0 = std::max(0, static_cast<int>(std::lround(c.x() - w)));
    const int x1 = std::min(width_ - 1, static_cast<int>(std::lround(c.x() + w)) - 1);
    for (int x = x0; x <= x1; ++x) put(rgb, x, y, fill);
  }
  if (r < 1.0) put(rgb, static_cast<int>(c.x()), static_cast<int>(c.y()), fill);
}

void FrameRaster::polygon(std::span<std::uint8_t> rgb, std::span<const Vec2> px, Rgb fill) const {
  if (px.size() < 3) return;
  double lo = px[0].y(), hi = px[0].y();
  for (const Vec2& p : px) {
    lo = std::min(lo, p.y());
    hi = std::max(hi, p.y());
  }
  const int y0 = std::max(0, static_cast<int>(std::floor(lo)));
  const int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(hi)));
  std::array<double, 32> xs;
  for (int y = y0; y <= y1; ++y) {
    const double sy = y + 0.5;
    std::size_t n = 0;
    for (std::size_t k = 0; k < px.size() && n < xs.size(); ++k) {
      const Vec2& a = px[k];
      const Vec2& b = px[(k + 1) % px.size()];
      if ((a.y() <= sy) != (b.y() <= sy))
        xs[n++] = a.x() + (sy - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
    }
    std::sort(xs.begin(), xs.begin() + static_cast<long>(n));
    for (std::size_t k = 0; k + 1 < n; k += 2) {
      const int x0 = std::max(0, static_cast<int>(std::lround(xs[k])));
      const int x1 = std::min(width_ - 1, static_cast<int>(std::lround(xs[k + 1])) - 1);
      for (int x = x0; x <= x1; ++x) put(rgb, x, y, fill);
    }
  }
}

void FrameRaster::line(std::span<std::uint8_t> rgb, const Vec2& a, const Vec2& b,
                       Rgb colour) const {
  const double length = (b - a).norm();
  const int steps = std::min(100000, static_cast<int>(std::ceil(2.0 * length)) + 1);
  for (int k = 0; k <= steps; ++k) dot(rgb, a + (b - a) * (static_cast<double>(k) / steps), colour);
}

void FrameRaster::dot(std::span<std::uint8_t> rgb, const Vec2& p, Rgb colour) const {
  if (!(p.x() >= 0.0 && p.y() >= 0.0 && p.x() < width_ && p.y() < height_)) return;
  put(rgb, static_cast<int>(p.x()), static_cast<int>(p.y()), colour);
}

}  // namespace floornav
