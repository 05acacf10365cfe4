#include "floornav/io/ros2_definitions.hpp"

#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace floornav {

namespace {

/// Each type's own fields, as its .msg file lists them (types spelt as there).
const std::map<std::string_view, std::string_view>& definitions() {
  static const std::map<std::string_view, std::string_view> table = {
      {"builtin_interfaces/msg/Time", "int32 sec\nuint32 nanosec\n"},
      {"builtin_interfaces/msg/Duration", "int32 sec\nuint32 nanosec\n"},
      {"std_msgs/msg/Header", "builtin_interfaces/Time stamp\nstring frame_id\n"},
      {"std_msgs/msg/String", "string data\n"},
      {"std_msgs/msg/ColorRGBA", "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n"},
      {"geometry_msgs/msg/Point", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/msg/Vector3", "float64 x\nfloat64 y\nfloat64 z\n"},
      {"geometry_msgs/msg/Quaternion", "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n"},
      {"geometry_msgs/msg/Pose", "Point position\nQuaternion orientation\n"},
      {"geometry_msgs/msg/PoseStamped", "std_msgs/Header header\nPose pose\n"},
      {"geometry_msgs/msg/PoseWithCovariance", "Pose pose\nfloat64[36] covariance\n"},
      {"geometry_msgs/msg/Twist", "Vector3  linear\nVector3  angular\n"},
      {"geometry_msgs/msg/TwistWithCovariance", "Twist twist\nfloat64[36] covariance\n"},
      {"geometry_msgs/msg/Transform", "Vector3 translation\nQuaternion rotation\n"},
      {"geometry_msgs/msg/TransformStamped",
       "std_msgs/Header header\nstring child_frame_id\nTransform transform\n"},
      {"tf2_msgs/msg/TFMessage", "geometry_msgs/TransformStamped[] transforms\n"},
      {"nav_msgs/msg/Odometry",
       "std_msgs/Header header\nstring child_frame_id\ngeometry_msgs/PoseWithCovariance pose\n"
       "geometry_msgs/TwistWithCovariance twist\n"},
      {"nav_msgs/msg/MapMetaData",
       "builtin_interfaces/Time map_load_time\nfloat32 resolution\nuint32 width\nuint32 height\n"
       "geometry_msgs/Pose origin\n"},
      {"nav_msgs/msg/OccupancyGrid", "std_msgs/Header header\nMapMetaData info\nint8[] data\n"},
      {"rosgraph_msgs/msg/Clock", "builtin_interfaces/Time clock\n"},
      {"sensor_msgs/msg/LaserScan",
       "std_msgs/Header header\nfloat32 angle_min\nfloat32 angle_max\nfloat32 angle_increment\n"
       "float32 time_increment\nfloat32 scan_time\nfloat32 range_min\nfloat32 range_max\n"
       "float32[] ranges\nfloat32[] intensities\n"},
      {"sensor_msgs/msg/Range",
       "std_msgs/Header header\nuint8 ULTRASOUND=0\nuint8 INFRARED=1\nuint8 radiation_type\n"
       "float32 field_of_view\nfloat32 min_range\nfloat32 max_range\nfloat32 range\n"
       "float32 variance\n"},
      {"sensor_msgs/msg/CompressedImage", "std_msgs/Header header\nstring format\nuint8[] data\n"},
      {"visualization_msgs/msg/UVCoordinate", "float32 u\nfloat32 v\n"},
      {"visualization_msgs/msg/MeshFile", "string filename\nuint8[] data\n"},
      {"visualization_msgs/msg/Marker",
       "int32 ARROW=0\nint32 CUBE=1\nint32 SPHERE=2\nint32 CYLINDER=3\nint32 LINE_STRIP=4\n"
       "int32 LINE_LIST=5\nint32 CUBE_LIST=6\nint32 SPHERE_LIST=7\nint32 POINTS=8\n"
       "int32 TEXT_VIEW_FACING=9\nint32 MESH_RESOURCE=10\nint32 TRIANGLE_LIST=11\n"
       "int32 ARROW_STRIP=12\nint32 ADD=0\nint32 MODIFY=0\nint32 DELETE=2\nint32 DELETEALL=3\n"
       "std_msgs/Header header\nstring ns\nint32 id\nint32 type\nint32 action\n"
       "geometry_msgs/Pose pose\ngeometry_msgs/Vector3 scale\nstd_msgs/ColorRGBA color\n"
       "builtin_interfaces/Duration lifetime\nbool frame_locked\ngeometry_msgs/Point[] points\n"
       "std_msgs/ColorRGBA[] colors\nstring texture_resource\n"
       "sensor_msgs/CompressedImage texture\nUVCoordinate[] uv_coordinates\nstring text\n"
       "string mesh_resource\nMeshFile mesh_file\nbool mesh_use_embedded_materials\n"},
      {"visualization_msgs/msg/MarkerArray", "Marker[] markers\n"},
  };
  return table;
}

const std::set<std::string_view> kPrimitives = {"bool",   "byte",  "char",   "float32", "float64",
                                                "int8",   "uint8", "int16",  "uint16",  "int32",
                                                "uint32", "int64", "uint64", "string"};

/// "pkg/msg/Type" -> "pkg".
std::string_view package_of(std::string_view type) {
  return type.substr(0, type.find('/'));
}

/// The types a definition uses, as rosbag2 names them: "pkg/Type" (a type without a package is
/// the definition's own package's), in name order.
std::set<std::string> dependencies(std::string_view text, std::string_view package) {
  std::set<std::string> out;
  std::istringstream lines{std::string(text)};
  for (std::string line; std::getline(lines, line);) {
    std::string type = line.substr(0, line.find(' '));
    if (const auto bracket = type.find('['); bracket != std::string::npos) type.resize(bracket);
    if (type.empty() || kPrimitives.count(type) != 0) continue;
    out.insert(type.find('/') == std::string::npos ? std::string(package) + "/" + type : type);
  }
  return out;
}

const std::string_view& lookup(const std::string& type) {
  const auto it = definitions().find(type);
  if (it == definitions().end())
    throw std::invalid_argument("no ROS 2 message definition for " + type);
  return it->second;
}

}  // namespace

std::string ros2_message_definition(std::string_view type) {
  std::set<std::string> seen;
  // rosbag2's order: a definition, then each of its dependencies not yet written, each followed
  // at once by its own.
  std::function<std::string(const std::string&)> full = [&](const std::string& name) {
    std::string text(lookup(name));
    for (const std::string& dep : dependencies(text, package_of(name))) {
      if (!seen.insert(dep).second) continue;
      const std::string key =
          std::string(package_of(dep)) + "/msg/" + dep.substr(dep.find('/') + 1);
      text += "\n" + std::string(80, '=') + "\nMSG: " + dep + "\n" + full(key);
    }
    return text;
  };
  return full(std::string(type));
}

}  // namespace floornav
