#include "floornav/io/ros2_messages.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>

namespace floornav {

namespace {

void time(CdrWriter& w, std::uint64_t ns) {  // builtin_interfaces/msg/Time
  w.i32(static_cast<std::int32_t>(ns / 1'000'000'000u));
  w.u32(static_cast<std::uint32_t>(ns % 1'000'000'000u));
}

void header(CdrWriter& w, std::uint64_t stamp, std::string_view frame) {
  time(w, stamp);
  w.string(frame);
}

void point(CdrWriter& w, double x, double y, double z) {
  w.f64(x);
  w.f64(y);
  w.f64(z);
}

void yaw_quaternion(CdrWriter& w, double yaw) {
  const Ros2Yaw q = ros2_yaw(yaw);
  point(w, 0.0, 0.0, q.z);
  w.f64(q.w);
}

void pose(CdrWriter& w, double x, double y, double z, double yaw) {  // geometry_msgs/msg/Pose
  point(w, x, y, z);
  yaw_quaternion(w, yaw);
}

constexpr std::array<double, 36> kNoCovariance{};

/// A little-endian field of a template, overwritten in place.
template <class T>
void patch(std::string& bytes, std::size_t at, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if constexpr (std::endian::native == std::endian::big) std::reverse(b, b + sizeof(T));
  std::memcpy(bytes.data() + at, b, sizeof(T));
}

void patch_time(std::string& bytes, std::size_t at, std::uint64_t ns) {
  patch(bytes, at, static_cast<std::int32_t>(ns / 1'000'000'000u));
  patch(bytes, at + 4, static_cast<std::uint32_t>(ns % 1'000'000'000u));
}

/// Position x, y (z stays 0) and orientation z, w (x, y stay 0) of a geometry_msgs/msg/Pose (or
/// Transform: the same seven float64) at `at`.
void patch_pose(std::string& bytes, std::size_t at, double x, double y, Ros2Yaw q) {
  patch(bytes, at, x);
  patch(bytes, at + 8, y);
  patch(bytes, at + 40, q.z);
  patch(bytes, at + 48, q.w);
}

}  // namespace

Ros2Yaw ros2_yaw(double yaw) {
  return {std::sin(0.5 * yaw), std::cos(0.5 * yaw)};
}

Ros2PoseMessages::Ros2PoseMessages(std::string_view frame, std::string_view child) {
  CdrWriter w;  // the layouts of encode_odometry and encode_tf, with where each patch goes
  w.begin();
  odometry_.stamp_at = w.next_at(4);
  header(w, 0, frame);
  w.string(child);
  odometry_.pose_at = w.next_at(8);
  pose(w, 0.0, 0.0, 0.0, 0.0);
  w.f64_array(kNoCovariance);
  odometry_.twist_at = w.next_at(8);
  point(w, 0.0, 0.0, 0.0);
  point(w, 0.0, 0.0, 0.0);
  w.f64_array(kNoCovariance);
  odometry_.bytes = w.data();

  w.begin();
  w.sequence_size(1);
  tf_.stamp_at = w.next_at(4);
  header(w, 0, frame);
  w.string(child);
  tf_.pose_at = w.next_at(8);
  point(w, 0.0, 0.0, 0.0);
  yaw_quaternion(w, 0.0);
  tf_.bytes = w.data();
}

std::string_view Ros2PoseMessages::odometry(std::uint64_t stamp, double x, double y, Ros2Yaw yaw,
                                            double v, double omega) {
  patch_time(odometry_.bytes, odometry_.stamp_at, stamp);
  patch_pose(odometry_.bytes, odometry_.pose_at, x, y, yaw);
  patch(odometry_.bytes, odometry_.twist_at, v);           // twist.linear.x
  patch(odometry_.bytes, odometry_.twist_at + 40, omega);  // twist.angular.z
  return odometry_.bytes;
}

std::string_view Ros2PoseMessages::tf(std::uint64_t stamp, double x, double y, Ros2Yaw yaw) {
  patch_time(tf_.bytes, tf_.stamp_at, stamp);
  patch_pose(tf_.bytes, tf_.pose_at, x, y, yaw);
  return tf_.bytes;
}

void encode_odometry(CdrWriter& w, std::uint64_t stamp, std::string_view frame,
                     std::string_view child, double x, double y, double yaw, double v,
                     double omega) {
  w.begin();
  header(w, stamp, frame);
  w.string(child);
  pose(w, x, y, 0.0, yaw);
  w.f64_array(kNoCovariance);
  point(w, v, 0.0, 0.0);  // twist in the child frame: forward speed, turn rate
  point(w, 0.0, 0.0, omega);
  w.f64_array(kNoCovariance);
}

void encode_tf(CdrWriter& w, std::span<const Ros2Transform> transforms) {
  w.begin();
  w.sequence_size(transforms.size());
  for (const Ros2Transform& t : transforms) {
    header(w, t.stamp, t.parent);
    w.string(t.child);
    point(w, t.x, t.y, 0.0);
    yaw_quaternion(w, t.yaw);
  }
}

void encode_laser_scan(CdrWriter& w, std::uint64_t stamp, std::string_view frame,
                       const Ros2ScanShape& shape, std::span<const float> ranges) {
  w.begin();
  header(w, stamp, frame);
  w.f32(shape.angle_min);
  w.f32(shape.angle_max);
  w.f32(shape.angle_increment);
  w.f32(0.0f);  // time_increment: every beam at once
  w.f32(shape.scan_time);
  w.f32(shape.range_min);
  w.f32(shape.range_max);
  w.f32_sequence(ranges);
  w.sequence_size(0);  // no intensities
}

void encode_range(CdrWriter& w, std::uint64_t stamp, std::string_view frame,
                  Ros2Radiation radiation, float field_of_view, float min_range, float max_range,
                  float range) {
  w.begin();
  header(w, stamp, frame);
  w.u8(static_cast<std::uint8_t>(radiation));
  w.f32(field_of_view);
  w.f32(min_range);
  w.f32(max_range);
  w.f32(range);
  w.f32(0.0f);  // variance: unknown
}

void encode_string(CdrWriter& w, std::string_view text) {
  w.begin();
  w.string(text);
}

void encode_pose_stamped(CdrWriter& w, std::uint64_t stamp, std::string_view frame, double x,
                         double y, double yaw) {
  w.begin();
  header(w, stamp, frame);
  pose(w, x, y, 0.0, yaw);
}

void encode_clock(CdrWriter& w, std::uint64_t stamp) {
  w.begin();
  time(w, stamp);
}

void encode_occupancy_grid(CdrWriter& w, std::uint64_t stamp, std::string_view frame,
                           float resolution, std::uint32_t width, std::uint32_t height,
                           double origin_x, double origin_y, double origin_yaw,
                           std::span<const std::int8_t> cells) {
  w.begin();
  header(w, stamp, frame);
  time(w, stamp);  // map_load_time
  w.f32(resolution);
  w.u32(width);
  w.u32(height);
  pose(w, origin_x, origin_y, 0.0, origin_yaw);
  w.i8_sequence(cells);
}

void encode_marker_array(CdrWriter& w, std::span<const Ros2Marker> markers) {
  w.begin();
  w.sequence_size(markers.size());
  for (const Ros2Marker& m : markers) {
    header(w, m.stamp, m.frame);
    w.string(m.ns);
    w.i32(m.id);
    w.i32(m.type);
    w.i32(0);  // ADD (or replace the marker of the same ns and id)
    pose(w, m.x, m.y, m.z, m.yaw);
    point(w, m.scale[0], m.scale[1], m.scale[2]);
    for (float c : m.color) w.f32(c);
    w.i32(0);  // lifetime: forever (until replaced)
    w.u32(0);
    w.boolean(m.frame_locked);
    w.sequence_size(m.points.size());
    for (const auto& p : m.points) point(w, p[0], p[1], p[2]);
    w.sequence_size(0);  // colors
    w.string("");        // texture_resource
    header(w, 0, "");    // texture: sensor_msgs/msg/CompressedImage, empty
    w.string("");
    w.sequence_size(0);
    w.sequence_size(0);  // uv_coordinates
    w.string(m.text);
    w.string("");  // mesh_resource
    w.string("");  // mesh_file: filename, data
    w.sequence_size(0);
    w.boolean(false);  // mesh_use_embedded_materials
  }
}

}  // namespace floornav
