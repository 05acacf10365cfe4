#pragma once
/// @file
/// ROS 2 messages of a run's bag, encoded to CDR (cdr_writer.hpp) field by field in the order of
/// their definitions (ros2_definitions.hpp). Each encode_* function starts a new message in the
/// writer. Times are nanoseconds of simulated time; poses are planar (z = 0, a yaw).

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "floornav/io/cdr_writer.hpp"

namespace floornav {

/// A transform from `parent` to `child` at `stamp`: a planar pose of the child in the parent.
struct Ros2Transform {
  std::uint64_t stamp{0};
  std::string_view parent;
  std::string_view child;
  double x{0.0}, y{0.0}, yaw{0.0};
};

/// sensor_msgs/msg/LaserScan's fields besides the header and the ranges.
struct Ros2ScanShape {
  float angle_min{0.0f}, angle_max{0.0f}, angle_increment{0.0f};  ///< rad
  float scan_time{0.0f};                                          ///< s between two scans
  float range_min{0.0f}, range_max{0.0f};                         ///< m
};

/// visualization_msgs/msg/Marker (the fields a run uses; the rest are written empty).
struct Ros2Marker {
  enum Type : std::int32_t { kCube = 1, kSphere = 2, kCylinder = 3, kLineStrip = 4 };
  std::uint64_t stamp{0};
  std::string frame;
  std::string ns;
  std::int32_t id{0};
  std::int32_t type{kCube};
  double x{0.0}, y{0.0}, z{0.0}, yaw{0.0};             ///< the pose
  std::array<double, 3> scale{1.0, 1.0, 1.0};          ///< m
  std::array<float, 4> color{0.5f, 0.5f, 0.5f, 1.0f};  ///< r, g, b, a in [0, 1]
  bool frame_locked{false};                            ///< moves with its frame
  std::vector<std::array<double, 3>> points;           ///< LINE_STRIP's points, in the pose's frame
  std::string text;
};

/// sensor_msgs/msg/Range's radiation types.
enum class Ros2Radiation : std::uint8_t { Ultrasound = 0, Infrared = 1 };

/// The orientation of a planar yaw as a quaternion: (0, 0, sin(yaw / 2), cos(yaw / 2)).
struct Ros2Yaw {
  double z{0.0}, w{1.0};
};
Ros2Yaw ros2_yaw(double yaw);

/// A robot's pose at each row as its bag publishes it twice: nav_msgs/msg/Odometry and a
/// tf2_msgs/msg/TFMessage of one transform, `frame` -> `child`. Each is encoded once with its
/// frames; a row patches the stamp, the pose and the twist into it (the bytes encode_odometry and
/// encode_tf write, without encoding 763 bytes field by field, 576 of them zero covariances).
class Ros2PoseMessages {
 public:
  Ros2PoseMessages(std::string_view frame, std::string_view child);
  /// The Odometry; valid until the next call.
  std::string_view odometry(std::uint64_t stamp, double x, double y, Ros2Yaw yaw, double v,
                            double omega);
  /// The TFMessage; valid until the next call.
  std::string_view tf(std::uint64_t stamp, double x, double y, Ros2Yaw yaw);

 private:
  struct Template {
    std::string bytes;
    std::size_t stamp_at{0}, pose_at{0}, twist_at{0};
  };
  Template odometry_, tf_;
};

void encode_odometry(CdrWriter& w, std::uint64_t stamp, std::string_view frame,
                     std::string_view child, double x, double y, double yaw, double v,
                     double omega);
void encode_tf(CdrWriter& w, std::span<const Ros2Transform> transforms);
void encode_laser_scan(CdrWriter& w, std::uint64_t stamp, std::string_view frame,
                       const Ros2ScanShape& shape, std::span<const float> ranges);
void encode_range(CdrWriter& w, std::uint64_t stamp, std::string_view frame,
                  Ros2Radiation radiation, float field_of_view, float min_range, float max_range,
                  float range);
void encode_string(CdrWriter& w, std::string_view text);
void encode_pose_stamped(CdrWriter& w, std::uint64_t stamp, std::string_view frame, double x,
                         double y, double yaw);
void encode_clock(CdrWriter& w, std::uint64_t stamp);
/// nav_msgs/msg/OccupancyGrid: `cells` row-major from the origin's corner, 0 free, 100
/// occupied, -1 unknown.
void encode_occupancy_grid(CdrWriter& w, std::uint64_t stamp, std::string_view frame,
                           float resolution, std::uint32_t width, std::uint32_t height,
                           double origin_x, double origin_y, double origin_yaw,
                           std::span<const std::int8_t> cells);
void encode_marker_array(CdrWriter& w, std::span<const Ros2Marker> markers);

}  // namespace floornav
