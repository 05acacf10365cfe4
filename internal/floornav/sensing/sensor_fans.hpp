#pragma once
/// @file
/// How the simulator casts a robot's range sensors (range_sensor.hpp) every step: the beams
/// composed with the robot's pose, the sensor list's lidars and fans found once (SensorLayout),
/// the fans cast with the caller's scratch. The same ranges and noise draws as the whole casts of
/// range_sensor.hpp, bit for bit; internal to floornav (the simulator and its tests).

#include <span>
#include <vector>

#include "floornav/core/rng.hpp"
#include "floornav/geometry/circle.hpp"
#include "floornav/geometry/oriented_box.hpp"
#include "floornav/geometry/pose2.hpp"
#include "floornav/sensing/range_sensor.hpp"
#include "floornav/world/world.hpp"

namespace floornav {

/// A disc known to hold no obstacle shape (circles, polygons, outside of the bounds; an occupancy
/// grid is not counted): beams starting strictly inside it skip World's inside test. Radius 0
/// (the default) claims nothing.
struct FreeDisc {
  Vec2 centre{Vec2::Zero()};  ///< m, world frame
  double radius{0.0};         ///< m
};

/// The direction (cos, sin) of a sensor's mount heading, in the robot frame.
Vec2 mount_direction(const RangeSensorSpec& sensor);

/// Writes the world-frame beam of each of `sensors` mounted on `robot` to `beams` (same size):
/// the origin is `robot.compose(mount)`'s position, bit for bit; the heading is the exact sum
/// robot.theta + mount.theta wrapped by whole turns; the direction is the mount's
/// (mount_direction) turned by the robot's heading, the chapter's composition of the sensor frame
/// with the robot frame: within 1e-15 of (cos, sin) of the heading, with the robot's sine
/// and cosine taken once for all sensors. A lidar (a run of at least 16 single-beam sensors on one
/// mount point, evenly spaced in heading) turns each beam's direction from the previous one: within
/// 1e-13 of the exact direction. No allocation.
void compute_sensor_beams(const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                          std::span<SensorBeam> beams);

/// What compute_sensor_beams and sense_ranges would look for in a sensor list at every step,
/// found once for a list that does not change (a robot's): its lidars (runs of at least 16
/// evenly turned single-beam sensors on one mount point, with the turn between beams) and, per
/// sensor, the end of its fan (single-beam sensors from it on the same mount point with the same
/// max_range). Valid only with the list it was built from.
class SensorLayout {
 public:
  SensorLayout() = default;
  explicit SensorLayout(std::span<const RangeSensorSpec> sensors);

  /// A lidar: sensors [begin, end), each beam turned from the previous by `turn` (cos, sin).
  struct Lidar {
    std::size_t begin{0};
    std::size_t end{0};
    Vec2 turn{1.0, 0.0};
  };
  /// The sensors it was built from.
  std::size_t size() const { return min_range_.size(); }
  /// In order, not overlapping.
  std::span<const Lidar> lidars() const { return lidars_; }
  /// Whether the run from `i` (to fan_end(i); `i` where such a run starts) has mount angles
  /// evenly spaced modulo 2 pi, to within half the fan's tolerance: its beams' headings are then
  /// evenly spaced at every pose, and their fan need not check it per beam.
  bool even_run(std::size_t i) const { return even_run_[i] != 0; }
  /// The end of the run of single-beam sensors from `i` on `i`'s mount point with `i`'s
  /// max_range (i itself when `i` is a cone).
  std::size_t fan_end(std::size_t i) const { return fan_end_[i]; }
  /// Each sensor's min_range and max_range, contiguous (the noiseless clamp of a fan).
  std::span<const double> min_ranges() const { return min_range_; }
  std::span<const double> max_ranges() const { return max_range_; }
  /// Each sensor's mount angle (rad, robot frame), contiguous.
  std::span<const double> mount_thetas() const { return mount_theta_; }
  /// Sensor `i`'s mount direction (cos, sin) in the robot frame (mount_direction).
  const Vec2& mount_dir(std::size_t i) const { return mount_dir_[i]; }

 private:
  std::vector<Lidar> lidars_;
  std::vector<std::size_t> fan_end_;
  std::vector<char> even_run_;
  std::vector<double> max_range_;
  std::vector<double> min_range_;
  std::vector<double> mount_theta_;
  std::vector<Vec2> mount_dir_;
};

/// compute_sensor_beams above with the lidars of `layout` (built from `sensors`) rather than
/// looked for: the same beams, bit for bit.
void compute_sensor_beams(const Pose2& robot, std::span<const RangeSensorSpec> sensors,
                          const SensorLayout& layout, std::span<SensorBeam> beams);
/// The same, with `heading` = (cos, sin) of `robot.theta` taken by the caller, who may use them
/// again at this pose (integrate_unicycle).
void compute_sensor_beams(const Pose2& robot, const Vec2& heading,
                          std::span<const RangeSensorSpec> sensors, const SensorLayout& layout,
                          std::span<SensorBeam> beams);

/// `sense_ranges` below, from beams already computed (`beams[i]` belongs to `sensors[i]`).
/// Beams starting inside `free` skip the inside-obstacle test, and a beam whose whole reach lies
/// inside it does not walk the world's cells at all (only the occupancy grid is cast); the ranges
/// are the same. A run of
/// at least 16 consecutive single-beam sensors with one origin and one max_range (a lidar) is cast
/// as one fan (`World::cast_fan`), again with the same ranges and the same noise draws.
/// `others` are further solid discs the rays hit besides the world: the bodies of other robots
/// (and of people); `boxes` are solid moving rectangles (forklifts). Each costs nothing when empty.
/// The fans work in `scratch` (one per thread; no allocation once it has grown).
void sense_ranges(const World& world, std::span<const SensorBeam> beams,
                  std::span<const RangeSensorSpec> sensors, double noise_stddev, Rng& rng,
                  std::span<double> ranges, FanScratch& scratch, const FreeDisc& free = {},
                  std::span<const Circle> others = {}, std::span<const OrientedBox> boxes = {});
/// The same with the fans of `layout` (built from `sensors`; `beams` computed from `sensors`)
/// rather than looked for beam by beam: the same ranges and noise draws, bit for bit.
void sense_ranges(const World& world, std::span<const SensorBeam> beams,
                  std::span<const RangeSensorSpec> sensors, const SensorLayout& layout,
                  double noise_stddev, Rng& rng, std::span<double> ranges, FanScratch& scratch,
                  const FreeDisc& free = {}, std::span<const Circle> others = {},
                  std::span<const OrientedBox> boxes = {});
/// The same with fan scratch of its own (allocated per call when a lidar is cast).
void sense_ranges(const World& world, std::span<const SensorBeam> beams,
                  std::span<const RangeSensorSpec> sensors, double noise_stddev, Rng& rng,
                  std::span<double> ranges, const FreeDisc& free = {},
                  std::span<const Circle> others = {}, std::span<const OrientedBox> boxes = {});

/// `ranges_to_points` below, from beams already computed and the sensors' max_ranges
/// (SensorLayout::max_ranges: contiguous, where the specs are 56 bytes apart).
std::size_t ranges_to_points(std::span<const SensorBeam> beams, std::span<const double> max_ranges,
                             std::span<const double> ranges, std::span<Vec2> points);

}  // namespace floornav
