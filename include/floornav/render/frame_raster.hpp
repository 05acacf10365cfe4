#pragma once
/// @file
/// Pictures of a floor as RGB pixels, fast enough to record every episode of a training run:
/// the world is rasterised once (obstacles filled, walls and edges stroked), and each frame
/// copies that picture and draws the moving bodies on it (robots with their heading and goal,
/// their sensor returns, people, forklifts). Row 0 is the top of the picture (north up), three
/// bytes per pixel (red, green, blue), rows packed: what numpy's (height, width, 3) uint8 holds.
/// The colours are trajectory.svg's.

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "floornav/geometry/box2.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/oriented_box.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

struct Rgb {
  std::uint8_t r{0}, g{0}, b{0};
};

/// "#rrggbb" -> Rgb (black for anything else).
Rgb rgb_of(std::string_view hex);

/// A robot as a frame shows it.
struct FrameRobot {
  Pose2 pose{};
  double radius{0.0};               ///< m: the body disc
  std::span<const Vec2> footprint;  ///< robot frame; empty: the disc
  std::optional<Vec2> goal;         ///< its current goal, marked with a cross
  std::span<const Vec2> returns;    ///< sensor returns (world frame), drawn as dots
  Rgb colour{};
};

class FrameRaster {
 public:
  /// Rasterises `world` over `area` (default: its bounds, else its extent, with a margin)
  /// fitted into height x width pixels, centred, the aspect kept.
  FrameRaster(const World& world, int height, int width, std::optional<Box2> area = {});

  int height() const { return height_; }
  int width() const { return width_; }
  std::size_t bytes() const { return background_.size(); }

  /// Draws a frame into `rgb` (bytes() long): the world, the people (discs), the forklifts
  /// (rectangles), then the robots.
  void draw(std::span<std::uint8_t> rgb, std::span<const FrameRobot> robots,
            std::span<const Circle> people = {}, std::span<const OrientedBox> forklifts = {}) const;

  /// Pixel coordinates (column, row; fractional) of world point `p`.
  Vec2 to_pixel(const Vec2& p) const { return {(p.x() - left_) * scale_, (top_ - p.y()) * scale_}; }

 private:
  void disc(std::span<std::uint8_t> rgb, const Vec2& centre, double radius, Rgb fill) const;
  void polygon(std::span<std::uint8_t> rgb, std::span<const Vec2> pixels, Rgb fill) const;
  void line(std::span<std::uint8_t> rgb, const Vec2& a, const Vec2& b, Rgb colour) const;
  void dot(std::span<std::uint8_t> rgb, const Vec2& p, Rgb colour) const;
  void put(std::span<std::uint8_t> rgb, int x, int y, Rgb c) const {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
    std::uint8_t* px = &rgb[3 * (static_cast<std::size_t>(y) * width_ + x)];
    px[0] = c.r;
    px[1] = c.g;
    px[2] = c.b;
  }

  int height_;
  int width_;
  double scale_{1.0};  ///< pixels per metre
  double left_{0.0};   ///< m: the world x of the picture's left edge
  double top_{0.0};    ///< m: the world y of its top edge
  std::vector<std::uint8_t> background_;
};

}  // namespace floornav
