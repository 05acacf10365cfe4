#pragma once
/// @file
/// The ROS 2 message definitions a run's bag uses, in the `ros2msg` form rosbag2 stores as an
/// MCAP schema: the type's .msg text, then each type it uses (depth first, each package's types
/// in name order, each once) after a line of 80 '=' and a line `MSG: pkg/Type`. The fields,
/// constants and defaults are those of ROS 2 Jazzy's .msg files (Humble's are the same but for
/// sensor_msgs/msg/Range, which gained `variance` at the end); their comments are left out.

#include <string>
#include <string_view>

namespace floornav {

/// The complete definition of `type` ("nav_msgs/msg/Odometry"); throws std::invalid_argument for
/// a type not in the table.
std::string ros2_message_definition(std::string_view type);

}  // namespace floornav
