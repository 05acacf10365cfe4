#include "floornav/io/sdf_world.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/angle.hpp"
#include "floornav/geometry/pose2.hpp"
#include "io/maps/text_parse.hpp"
#include "io/maps/xml_input.hpp"

namespace floornav {
namespace {

using tinyxml2::XMLElement;

/// The whitespace-separated numbers of an element's text; throws unless there are `count`.
std::vector<double> numbers(const XMLElement* e, std::size_t count, const std::string& file) {
  std::vector<double> out;
  const char* text = e->GetText();
  std::string_view rest = text != nullptr ? text : "";
  for (;;) {
    rest = io_detail::trim(rest);
    if (rest.empty()) break;
    const auto end = rest.find_first_of(" \t\r\n");
    const std::string_view token = rest.substr(0, end);
    const auto v = io_detail::parse_double(token);
    if (!v) {
      throw InputError(file, io_detail::where_of(e),
                       std::string("<") + e->Name() + ">: " +
                           io_detail::magnitude_problem(token).value_or(
                               "'" + std::string(token) + "' is not a finite number"));
    }
    out.push_back(*v);
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end);
  }
  if (out.size() != count) {
    throw InputError(file, io_detail::where_of(e),
                     std::string("<") + e->Name() + ">: expected " + std::to_string(count) +
                         " numbers, got " + std::to_string(out.size()));
  }
  return out;
}

/// A `<pose>` "x y z roll pitch yaw" as the planar pose (x, y, yaw).
Pose2 parse_pose(const XMLElement* pose, const std::string& file) {
  for (const char* attr : {"relative_to", "frame"}) {
    const char* frame = pose->Attribute(attr);
    if (frame != nullptr && *frame != '\0') {
      throw InputError(file, io_detail::where_of(pose),
                       std::string("<pose ") + attr + "='" + frame +
                           "'>: poses relative to other frames are not supported");
    }
  }
  const char* format = pose->Attribute("rotation_format");
  if (format != nullptr && std::string_view(format) != "euler_rpy") {
    throw InputError(file, io_detail::where_of(pose),
                     std::string("<pose rotation_format='") + format + "'> is not supported");
  }
  const std::vector<double> v = numbers(pose, 6, file);
  bool degrees = false;
  if (const char* d = pose->Attribute("degrees")) {
    const std::string_view t = io_detail::trim(d);
    if (t == "true" || t == "1") {
      degrees = true;
    } else if (t != "false" && t != "0") {
      throw InputError(file, io_detail::where_of(pose),
                       "<pose degrees='" + std::string(t.substr(0, 64)) +
                           "'>: expected true, false, 1 or 0 (SDF's boolean)");
    }
  }
  return Pose2{{v[0], v[1]}, wrap_angle(degrees ? deg_to_rad(v[5]) : v[5])};
}

/// The `<pose>` child of `parent`, or the identity.
Pose2 child_pose(const XMLElement* parent, const std::string& file) {
  const XMLElement* pose = parent->FirstChildElement("pose");
  return pose != nullptr ? parse_pose(pose, file) : Pose2{};
}

/// A positive size or radius.
double positive(const XMLElement* e, double v, const std::string& file) {
  if (!(v > 0.0)) {
    throw InputError(
        file, io_detail::where_of(e),
        std::string("<") + e->Name() + "> must be positive, got " + fmt::format("{:.6g}", v));
  }
  return v;
}

/// Whether `m` or a model nested in it has a <collision>.
bool has_collision(const XMLElement* m) {
  for (const XMLElement* link = m->FirstChildElement("link"); link != nullptr;
       link = link->NextSiblingElement("link"))
    if (link->FirstChildElement("collision") != nullptr) return true;
  for (const XMLElement* sub = m->FirstChildElement("model"); sub != nullptr;
       sub = sub->NextSiblingElement("model"))
    if (has_collision(sub)) return true;
  return false;
}

class SdfReader {
 public:
  SdfReader(std::string file, SdfWorld& out) : file_(std::move(file)), out_(out) {}

  /// A model (and its nested models) whose parent frame is `parent`.
  void model(const XMLElement* m, const Pose2& parent, bool parent_static, const std::string& name,
             const std::optional<Pose2>& state_pose) {
    const Pose2 pose = parent.compose(state_pose ? *state_pose : child_pose(m, file_));
    bool is_static = parent_static;
    if (const XMLElement* s = m->FirstChildElement("static")) {
      const char* text = s->GetText();
      const std::string_view t = io_detail::trim(text != nullptr ? text : "");
      if (t == "1" || t == "true") {
        is_static = true;
      } else if (t != "0" && t != "false") {
        throw InputError(file_, io_detail::where_of(s),
                         "<static> must be 0, 1, true or false, got '" + std::string(t) + "'");
      }
    }
    if (!is_static) {
      // A model that may move: its collisions are not a fixed obstacle. Reported (a robot would
      // drive through it) unless it has none.
      if (has_collision(m))
        out_.skipped.push_back(io_detail::where_of(m) + ": model '" + name +
                               "' is not static, so its collisions are not read");
      return;
    }
    for (const XMLElement* link = m->FirstChildElement("link"); link != nullptr;
         link = link->NextSiblingElement("link")) {
      const Pose2 link_pose = pose.compose(child_pose(link, file_));
      const char* link_name = link->Attribute("name");
      for (const XMLElement* c = link->FirstChildElement("collision"); c != nullptr;
           c = c->NextSiblingElement("collision")) {
        collision(c, link_pose.compose(child_pose(c, file_)),
                  name + "::" + (link_name != nullptr ? link_name : ""));
      }
    }
    for (const XMLElement* sub = m->FirstChildElement("model"); sub != nullptr;
         sub = sub->NextSiblingElement("model")) {
      const char* sub_name = sub->Attribute("name");
      model(sub, pose, is_static, name + "::" + (sub_name != nullptr ? sub_name : ""),
            std::nullopt);
    }
  }

 private:
  void collision(const XMLElement* c, const Pose2& pose, const std::string& owner) {
    const XMLElement* geometry = c->FirstChildElement("geometry");
    const XMLElement* shape = geometry != nullptr ? geometry->FirstChildElement() : nullptr;
    if (shape == nullptr) {
      throw InputError(file_, io_detail::where_of(c), "<collision> without a <geometry> shape");
    }
    const std::string kind = shape->Name();
    if (kind == "box") {
      const XMLElement* size = shape->FirstChildElement("size");
      if (size == nullptr)
        throw InputError(file_, io_detail::where_of(shape), "<box> lacks <size>");
      const std::vector<double> s = numbers(size, 3, file_);
      const double hx = 0.5 * positive(size, s[0], file_);
      const double hy = 0.5 * positive(size, s[1], file_);
      positive(size, s[2], file_);
      out_.polygons.push_back({pose.transform_point({-hx, -hy}), pose.transform_point({hx, -hy}),
                               pose.transform_point({hx, hy}), pose.transform_point({-hx, hy})});
    } else if (kind == "cylinder" || kind == "sphere") {
      const XMLElement* radius = shape->FirstChildElement("radius");
      if (radius == nullptr) {
        throw InputError(file_, io_detail::where_of(shape), "<" + kind + "> lacks <radius>");
      }
      out_.circles.push_back(
          Circle{pose.position, positive(radius, numbers(radius, 1, file_)[0], file_)});
    } else if (kind == "plane") {
      // The ground, unless it stands up: a vertical plane is a wall floornav cannot represent.
      if (const XMLElement* normal = shape->FirstChildElement("normal")) {
        const std::vector<double> n = numbers(normal, 3, file_);
        if (n[0] != 0.0 || n[1] != 0.0)
          out_.skipped.push_back(io_detail::where_of(shape) + ": model '" + owner +
                                 "': a <plane> that is not the ground (normal not 0 0 1)");
      }
    } else {
      out_.skipped.push_back(io_detail::where_of(shape) + ": model '" + owner + "': a <" + kind +
                             "> collision cannot be read (only <box>, <cylinder> and "
                             "<sphere>)");
    }
  }

  std::string file_;
  SdfWorld& out_;
};

}  // namespace

SdfWorld load_sdf_world(const std::filesystem::path& path) {
  const std::string file = path.string();
  tinyxml2::XMLDocument doc;
  io_detail::load_xml(path, doc);
  const XMLElement* sdf = doc.RootElement();
  if (sdf == nullptr || std::string_view(sdf->Name()) != "sdf") {
    throw InputError(file, sdf != nullptr ? io_detail::where_of(sdf) : "",
                     "expected an <sdf> root element");
  }
  SdfWorld out;
  SdfReader reader(file, out);
  const XMLElement* world = sdf->FirstChildElement("world");
  if (world != nullptr && world->NextSiblingElement("world") != nullptr) {
    throw InputError(file, io_detail::where_of(world->NextSiblingElement("world")),
                     "more than one <world>");
  }
  const XMLElement* scope = world != nullptr ? world : sdf;
  if (world == nullptr && sdf->FirstChildElement("model") == nullptr) {
    throw InputError(file, io_detail::where_of(sdf), "no <world> or <model> in this file");
  }

  // The saved state: a model's live pose (its <link> poses there are world-frame, not used).
  std::map<std::string, Pose2> state_poses;
  if (world != nullptr) {
    for (const XMLElement* state = world->FirstChildElement("state"); state != nullptr;
         state = state->NextSiblingElement("state")) {
      for (const XMLElement* m = state->FirstChildElement("model"); m != nullptr;
           m = m->NextSiblingElement("model")) {
        const char* name = m->Attribute("name");
        const XMLElement* pose = m->FirstChildElement("pose");
        if (name != nullptr && pose != nullptr) state_poses[name] = parse_pose(pose, file);
      }
    }
  }

  std::set<std::string> seen;
  for (const XMLElement* e = scope->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string_view kind = e->Name();
    if (kind == "include") {
      // The sun and the ground plane hold nothing a robot could hit; anything else included
      // (a model from Gazebo's database) is not read.
      const XMLElement* uri = e->FirstChildElement("uri");
      const char* text = uri != nullptr ? uri->GetText() : nullptr;
      const std::string_view u = io_detail::trim(text != nullptr ? text : "");
      if (u != "model://sun" && u != "model://ground_plane")
        out.skipped.push_back(io_detail::where_of(e) + ": <include> of '" +
                              std::string(u.substr(0, 200)) +
                              "' is not read (only models written in the file are)");
      continue;
    }
    if (kind != "model") continue;
    const char* name_attr = e->Attribute("name");
    const std::string name = name_attr != nullptr ? name_attr : "";
    if (!seen.insert(name).second) {
      throw InputError(file, io_detail::where_of(e), "duplicate model name '" + name + "'");
    }
    const auto state = state_poses.find(name);
    reader.model(e, Pose2{}, false, name,
                 state != state_poses.end() ? std::optional<Pose2>(state->second) : std::nullopt);
  }
  return out;
}

}  // namespace floornav
