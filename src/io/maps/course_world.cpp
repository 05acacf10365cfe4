#include "floornav/io/course_world.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <cmath>
#include <string>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/polygon.hpp"
#include "io/maps/xml_input.hpp"

namespace floornav {
namespace {

using tinyxml2::XMLElement;

// The simplicity check is quadratic in the points: bound them so that no file can make it hang.
constexpr std::size_t kMaxPolygonPoints = 1000;

/// The `<pose x y theta>` child of `parent`, required.
Pose2 read_pose(const XMLElement* parent, const std::string& file) {
  const XMLElement* pose = parent->FirstChildElement("pose");
  if (pose == nullptr) {
    throw InputError(file, io_detail::where_of(parent),
                     std::string("<") + parent->Name() + "> lacks a <pose x y theta>");
  }
  if (pose->NextSiblingElement("pose") != nullptr) {
    throw InputError(file, io_detail::where_of(pose->NextSiblingElement("pose")),
                     std::string("<") + parent->Name() + "> has more than one <pose>");
  }
  const double theta = io_detail::number_attribute(pose, "theta", file);
  if (std::abs(theta) > 2.0 * kPi + 1e-9) {
    throw InputError(
        file, io_detail::where_of(pose),
        fmt::format("<pose theta=\"{:.6g}\">: beyond +-2 pi: angles are in radians (if "
                    "you meant {:.6g} degrees, write {:.6g})",
                    theta, theta, deg_to_rad(theta)));
  }
  return Pose2{
      {io_detail::number_attribute(pose, "x", file), io_detail::number_attribute(pose, "y", file)},
      wrap_angle(theta)};
}

}  // namespace

CourseWorld load_course_world(const std::filesystem::path& xml) {
  const std::string file = xml.string();
  tinyxml2::XMLDocument doc;
  io_detail::load_xml(xml, doc);
  const XMLElement* sim = doc.RootElement();
  if (sim == nullptr || std::string(sim->Name()) != "simulation") {
    throw InputError(file, sim != nullptr ? io_detail::where_of(sim) : "",
                     "expected a <simulation> root element");
  }
  CourseWorld world;
  // The Sim.I.Am/pySimiam world elements; any other (a typo like <obstcle>) is an error, never
  // an obstacle dropped without a word.
  io_detail::check_children(sim, {"robot", "obstacle", "marker"}, file);
  for (const XMLElement* e = sim->FirstChildElement(); e != nullptr; e = e->NextSiblingElement()) {
    const std::string name = e->Name();
    if (name == "robot") {
      io_detail::check_children(e, {"supervisor", "pose"}, file);
      CourseRobot robot;
      const char* type = e->Attribute("type");
      if (type == nullptr || std::string(type).empty()) {
        throw InputError(file, io_detail::where_of(e), "<robot> lacks the attribute 'type'");
      }
      robot.type = type;
      robot.pose = read_pose(e, file);
      if (const XMLElement* sup = e->FirstChildElement("supervisor")) {
        if (const char* t = sup->Attribute("type")) robot.supervisor = t;
      }
      world.robots.push_back(std::move(robot));
    } else if (name == "obstacle") {
      io_detail::check_children(e, {"pose", "geometry", "color"}, file);
      const Pose2 pose = read_pose(e, file);
      const XMLElement* geometry = io_detail::single_child(e, "geometry", file);
      if (geometry == nullptr) {
        throw InputError(file, io_detail::where_of(e), "<obstacle> lacks a <geometry>");
      }
      io_detail::check_children(geometry, {"point"}, file);
      std::vector<Vec2> polygon;
      for (const XMLElement* p = geometry->FirstChildElement("point"); p != nullptr;
           p = p->NextSiblingElement("point")) {
        polygon.push_back(pose.transform_point({io_detail::number_attribute(p, "x", file),
                                                io_detail::number_attribute(p, "y", file)}));
      }
      if (polygon.size() > kMaxPolygonPoints) {
        throw InputError(file, io_detail::where_of(geometry),
                         "an obstacle has at most " + std::to_string(kMaxPolygonPoints) +
                             " <point>s, got " + std::to_string(polygon.size()));
      }
      if (polygon.size() < 3) {
        throw InputError(
            file, io_detail::where_of(e),
            "an obstacle needs at least 3 <point>s, got " + std::to_string(polygon.size()));
      }
      if (!is_simple(polygon)) {
        throw InputError(file, io_detail::where_of(geometry),
                         "the obstacle's polygon crosses itself or has repeated points (it must "
                         "be simple)");
      }
      world.obstacles.push_back(std::move(polygon));
    }
    // A <marker> (a goal flag of the course simulator) does not block a robot.
  }
  return world;
}

}  // namespace floornav
