// The CDR encoder against bytes worked out by hand from the XCDR1 rules (little-endian,
// alignment counted from the end of the 4-byte encapsulation header), and whole ROS 2 messages.
#include "floornav/io/cdr_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <tuple>
#include <vector>

#include "floornav/io/ros2_messages.hpp"

namespace floornav {
namespace {

std::vector<int> bytes(std::string_view s) {
  std::vector<int> out;
  for (char c : s) out.push_back(static_cast<unsigned char>(c));
  return out;
}

TEST(CdrWriter, StartsWithTheLittleEndianEncapsulationHeader) {
  CdrWriter w;
  w.begin();
  EXPECT_EQ(bytes(w.data()), (std::vector<int>{0x00, 0x01, 0x00, 0x00}));
  w.u8(7);
  w.begin();  // a new message: the old one is gone
  EXPECT_EQ(w.data().size(), 4u);
}

TEST(CdrWriter, AlignsEachPrimitiveToItsSizeAfterTheHeader) {
  CdrWriter w;
  w.begin();
  w.u8(0x01);         // offset 0
  w.f64(2.0);         // padded to offset 8: 0x4000000000000000
  w.u8(0x02);         // offset 16
  w.i32(-2);          // padded to 20: fe ff ff ff
  w.f32(1.0f);        // offset 24: 0x3f800000
  w.u32(0x01020304);  // offset 28
  const std::vector<int> expected = {
      0x00, 0x01, 0x00, 0x00,                    // header
      0x01, 0,    0,    0,    0, 0, 0,    0,     // u8 + 7 bytes of padding
      0,    0,    0,    0,    0, 0, 0x00, 0x40,  // 2.0
      0x02, 0,    0,    0,                       // u8 + 3 of padding
      0xfe, 0xff, 0xff, 0xff,                    // -2
      0x00, 0x00, 0x80, 0x3f,                    // 1.0f
      0x04, 0x03, 0x02, 0x01};                   // little-endian
  EXPECT_EQ(bytes(w.data()), expected);
}

TEST(CdrWriter, StringsCountTheirNulAndSequencesTheirElements) {
  CdrWriter w;
  w.begin();
  w.string("ab");  // length 3 (with the NUL), 'a', 'b', NUL: ends at offset 7
  w.f64(0.5);      // padded to 8 (one byte)
  const float values[] = {1.0f, -0.0f};
  w.f32_sequence(values);  // count at 16, values at 20 and 24
  w.string("");            // an empty string is its NUL alone: length 1
  const std::int8_t cells[] = {100, -1, 0};
  w.i8_sequence(cells);  // count aligned to 4 (offset 36), then the bytes
  const std::vector<int> expected = {
      0x00, 0x01, 0x00, 0x00,                                         //
      0x03, 0,    0,    0,    'a',  'b',  0x00, 0x00,                 // "ab" + 1 byte of padding
      0,    0,    0,    0,    0,    0,    0xe0, 0x3f,                 // 0.5
      0x02, 0,    0,    0,    0x00, 0x00, 0x80, 0x3f, 0, 0, 0, 0x80,  // [1.0f, -0.0f]
      0x01, 0,    0,    0,    0x00, 0,    0,    0,                    // "" + 3 of padding
      0x03, 0,    0,    0,    0x64, 0xff, 0x00};                      // [100, -1, 0]
  EXPECT_EQ(bytes(w.data()), expected);
}

TEST(CdrWriter, FixedArraysHaveNoCount) {
  CdrWriter w;
  w.begin();
  w.u8(9);
  const double three[] = {1.0, 2.0, 3.0};
  w.f64_array(three);
  EXPECT_EQ(w.data().size(), 4u + 8u + 24u);
  EXPECT_EQ(static_cast<unsigned char>(w.data()[4 + 8 + 7]), 0x3f);  // 1.0's top byte
}

TEST(Ros2Messages, ClockAndStringAsRosSerializesThem) {
  CdrWriter w;
  encode_clock(w, 1'500'000'000);  // 1 s and 500,000,000 ns = 0x1dcd6500
  EXPECT_EQ(bytes(w.data()), (std::vector<int>{0, 1, 0, 0, 1, 0, 0, 0, 0x00, 0x65, 0xcd, 0x1d}));
  encode_string(w, "hi");
  EXPECT_EQ(bytes(w.data()), (std::vector<int>{0, 1, 0, 0, 3, 0, 0, 0, 'h', 'i', 0}));
}

TEST(Ros2Messages, PoseStampedLayout) {
  CdrWriter w;
  encode_pose_stamped(w, 2'000'000'001, "map", 1.0, -1.0, 0.0);
  const std::vector<int> b = bytes(w.data());
  ASSERT_EQ(b.size(), 4u + 8u + 8u + 56u);  // header; stamp; "map"; 7 float64 (no padding)
  EXPECT_EQ((std::vector<int>(b.begin() + 4, b.begin() + 20)),
            (std::vector<int>{2, 0, 0, 0, 1, 0, 0, 0, 4, 0, 0, 0, 'm', 'a', 'p', 0}));
  EXPECT_EQ(b[20 + 7], 0x3f);  // position.x = 1.0
  EXPECT_EQ(b[28 + 7], 0xbf);  // position.y = -1.0
  EXPECT_EQ(b[68 + 7], 0x3f);  // orientation.w = cos(0) = 1.0
}

TEST(Ros2Messages, OdometryHasTwoCovariancesAndTheTwistInTheChildFrame) {
  CdrWriter w;
  encode_odometry(w, 0, "odom", "base_link", 1.0, 2.0, M_PI / 2, 0.3, -0.2);
  // After the 4-byte header: stamp 8, "odom" 9 (+3 padding), "base_link" 14 (+6 padding to the
  // first float64 at 40), pose 7 x 8, covariance 36 x 8, twist 6 x 8, covariance 36 x 8.
  EXPECT_EQ(w.data().size(), 4u + 40u + 56u + 288u + 48u + 288u);
  double yaw_z = 0.0, v = 0.0, omega = 0.0;
  std::memcpy(&yaw_z, w.data().data() + 4 + 40 + 40, 8);             // orientation.z
  std::memcpy(&v, w.data().data() + 4 + 40 + 56 + 288, 8);           // twist.linear.x
  std::memcpy(&omega, w.data().data() + 4 + 40 + 56 + 288 + 40, 8);  // twist.angular.z
  EXPECT_NEAR(yaw_z, std::sin(M_PI / 4), 1e-15);
  EXPECT_EQ(v, 0.3);
  EXPECT_EQ(omega, -0.2);
}

TEST(Ros2Messages, PoseTemplatesWriteTheBytesOfTheEncoders) {
  Ros2PoseMessages pose("robot_2/odom", "robot_2/base_link");
  CdrWriter w;
  for (const auto& [stamp, x, y, yaw, v, omega] :
       {std::tuple{0ull, 0.0, 0.0, 0.0, 0.0, 0.0},
        std::tuple{1'500'000'001ull, -3.25, 7.5, -2.9, 0.31, -1.2},
        std::tuple{86'400'000'000'123ull, 1e6, -1e-9, M_PI, -0.5, 2.0}}) {
    encode_odometry(w, stamp, "robot_2/odom", "robot_2/base_link", x, y, yaw, v, omega);
    EXPECT_EQ(pose.odometry(stamp, x, y, ros2_yaw(yaw), v, omega), w.data());
    const Ros2Transform t[] = {{stamp, "robot_2/odom", "robot_2/base_link", x, y, yaw}};
    encode_tf(w, t);
    EXPECT_EQ(pose.tf(stamp, x, y, ros2_yaw(yaw)), w.data());
  }
}

}  // namespace
}  // namespace floornav
