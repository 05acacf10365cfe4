#include "floornav/io/sdf_world.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <span>
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

// The elements SDF allows where floornav reads (sdformat.org/spec, 1.4 to 1.11), by parent. Any
// other child is refused with a "did you mean": a misspelt <modle>, <lnk> or <colision> would
// otherwise drop the obstacle it holds without a word. Of the allowed ones, those that can hold
// something a robot could hit and that floornav does not read (a <population>, an <actor> with
// collisions, an <include>) are reported in `skipped`; the rest (lights, physics, the GUI, ...)
// hold nothing to hit.
constexpr std::string_view kSdfChildren[] = {"world", "model", "actor", "light"};
constexpr std::string_view kWorldChildren[] = {
    "model",  "include", "actor",   "population",     "state",
    "audio",  "wind",    "gravity", "magnetic_field", "atmosphere",
    "gui",    "physics", "scene",   "light",          "spherical_coordinates",
    "plugin", "frame",   "road",    "joint"};
constexpr std::string_view kModelChildren[] = {
    "static",       "pose",  "link",    "model",   "joint",       "plugin",
    "self_collide", "frame", "gripper", "include", "enable_wind", "allow_auto_disable"};
constexpr std::string_view kLinkChildren[] = {"pose",
                                              "inertial",
                                              "collision",
                                              "visual",
                                              "sensor",
                                              "gravity",
                                              "self_collide",
                                              "kinematic",
                                              "must_be_base_link",
                                              "velocity_decay",
                                              "projector",
                                              "audio_sink",
                                              "audio_source",
                                              "battery",
                                              "light",
                                              "particle_emitter",
                                              "enable_wind"};
constexpr std::string_view kCollisionChildren[] = {"pose", "geometry", "laser_retro",
                                                   "max_contacts", "surface"};
constexpr std::string_view kShapes[] = {"box",   "cylinder", "sphere",    "plane",
                                        "mesh",  "capsule",  "ellipsoid", "heightmap",
                                        "image", "polyline", "empty"};

constexpr std::string_view kBoxChildren[] = {"size"};
constexpr std::string_view kCylinderChildren[] = {"radius", "length"};
constexpr std::string_view kSphereChildren[] = {"radius"};

/// Throws for the first child of `parent` not in `allowed`, naming it and the closest allowed.
void check_known(const XMLElement* parent, std::span<const std::string_view> allowed,
                 const std::string& file) {
  for (const XMLElement* e = parent->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string_view name = e->Name();
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
    throw InputError(file, io_detail::where_of(e),
                     "unknown element <" + std::string(name.substr(0, 64)) + "> in <" +
                         parent->Name() + ">" + io_detail::did_you_mean(name, allowed) +
                         ": what it holds would not be read");
  }
}

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

/// A frame in both forms: the planar pose (x, y, yaw) composed in 2D, exactly as an upright world
/// has always been read, and the full 3D transform, which decides once anything in the chain is
/// tilted (roll or pitch not 0).
struct Frame {
  Pose2 planar;
  Eigen::Isometry3d spatial{Eigen::Isometry3d::Identity()};
  bool tilted{false};

  Frame compose(const Frame& child) const {
    return {planar.compose(child.planar), spatial * child.spatial, tilted || child.tilted};
  }
};

/// A `<pose>` "x y z roll pitch yaw" (SDF: rotation Rz(yaw) Ry(pitch) Rx(roll)).
Frame parse_pose(const XMLElement* pose, const std::string& file) {
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
  const auto angle = [&](double a) { return degrees ? deg_to_rad(a) : a; };
  Frame f;
  f.planar = Pose2{{v[0], v[1]}, wrap_angle(angle(v[5]))};
  f.tilted = v[3] != 0.0 || v[4] != 0.0;
  f.spatial = Eigen::Translation3d(v[0], v[1], v[2]) *
              Eigen::AngleAxisd(angle(v[5]), Eigen::Vector3d::UnitZ()) *
              Eigen::AngleAxisd(angle(v[4]), Eigen::Vector3d::UnitY()) *
              Eigen::AngleAxisd(angle(v[3]), Eigen::Vector3d::UnitX());
  return f;
}

/// The one `<pose>` child of `parent` (a second is an error: which one was meant?), or identity.
Frame child_pose(const XMLElement* parent, const std::string& file) {
  const XMLElement* pose = io_detail::single_child(parent, "pose", file);
  return pose != nullptr ? parse_pose(pose, file) : Frame{};
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

/// Whether `e` holds a <collision> anywhere below it.
bool holds_collision(const XMLElement* e) {
  for (const XMLElement* c = e->FirstChildElement(); c != nullptr; c = c->NextSiblingElement())
    if (std::string_view(c->Name()) == "collision" || holds_collision(c)) return true;
  return false;
}

/// The convex hull of `pts`, counter-clockwise (Andrew's monotone chain), without collinear
/// points: the ground shadow of a tilted shape.
std::vector<Vec2> convex_hull(std::vector<Vec2> pts) {
  std::sort(pts.begin(), pts.end(), [](const Vec2& a, const Vec2& b) {
    return a.x() != b.x() ? a.x() < b.x() : a.y() < b.y();
  });
  const auto cross = [](const Vec2& o, const Vec2& a, const Vec2& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Vec2> hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0.0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0.0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k > 0 ? k - 1 : 0);
  return hull;
}

Vec2 ground(const Eigen::Vector3d& p) {
  return {p.x(), p.y()};
}

class SdfReader {
 public:
  SdfReader(std::string file, SdfWorld& out) : file_(std::move(file)), out_(out) {}

  /// A model (and its nested models) whose parent frame is `parent`.
  void model(const XMLElement* m, const Frame& parent, bool parent_static, const std::string& name,
             const std::optional<Frame>& state_pose) {
    check_structure(m);
    const Frame pose = parent.compose(state_pose ? *state_pose : child_pose(m, file_));
    bool is_static = parent_static;
    if (const XMLElement* s = io_detail::single_child(m, "static", file_)) {
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
      if (holds_collision(m))
        out_.skipped.push_back(io_detail::where_of(m) + ": model '" + name +
                               "' is not static, so its collisions are not read");
      return;
    }
    for (const XMLElement* inc = m->FirstChildElement("include"); inc != nullptr;
         inc = inc->NextSiblingElement("include"))
      out_.skipped.push_back(io_detail::where_of(inc) + ": model '" + name +
                             "': an <include> is not read (only models written in the file are)");
    for (const XMLElement* link = m->FirstChildElement("link"); link != nullptr;
         link = link->NextSiblingElement("link")) {
      const Frame link_pose = pose.compose(child_pose(link, file_));
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
  /// Every element of a model's tree is one SDF allows there, and a link, collision or geometry
  /// holds what it may once: checked for static and moving models alike.
  void check_structure(const XMLElement* m) {
    check_known(m, kModelChildren, file_);
    io_detail::single_child(m, "pose", file_);
    for (const XMLElement* link = m->FirstChildElement("link"); link != nullptr;
         link = link->NextSiblingElement("link")) {
      check_known(link, kLinkChildren, file_);
      io_detail::single_child(link, "pose", file_);
      for (const XMLElement* c = link->FirstChildElement("collision"); c != nullptr;
           c = c->NextSiblingElement("collision")) {
        check_known(c, kCollisionChildren, file_);
        io_detail::single_child(c, "pose", file_);
        if (const XMLElement* g = io_detail::single_child(c, "geometry", file_)) {
          check_known(g, kShapes, file_);
          const XMLElement* first = g->FirstChildElement();
          if (first != nullptr && first->NextSiblingElement() != nullptr)
            throw InputError(file_, io_detail::where_of(first->NextSiblingElement()),
                             std::string("<geometry> holds <") + first->Name() + "> and <" +
                                 first->NextSiblingElement()->Name() +
                                 ">: a geometry is one shape (give each its own <collision>)");
        }
      }
    }
  }

  void collision(const XMLElement* c, const Frame& pose, const std::string& owner) {
    const XMLElement* geometry = c->FirstChildElement("geometry");
    const XMLElement* shape = geometry != nullptr ? geometry->FirstChildElement() : nullptr;
    if (shape == nullptr) {
      throw InputError(file_, io_detail::where_of(c), "<collision> without a <geometry> shape");
    }
    const std::string kind = shape->Name();
    if (kind == "box") {
      check_known(shape, kBoxChildren, file_);
      const XMLElement* size = io_detail::single_child(shape, "size", file_);
      if (size == nullptr)
        throw InputError(file_, io_detail::where_of(shape), "<box> lacks <size>");
      const std::vector<double> s = numbers(size, 3, file_);
      const double hx = 0.5 * positive(size, s[0], file_);
      const double hy = 0.5 * positive(size, s[1], file_);
      const double hz = 0.5 * positive(size, s[2], file_);
      if (!pose.tilted) {
        const Pose2& p = pose.planar;
        out_.polygons.push_back({p.transform_point({-hx, -hy}), p.transform_point({hx, -hy}),
                                 p.transform_point({hx, hy}), p.transform_point({-hx, hy})});
        return;
      }
      // Tilted: the ground shadow of its eight corners.
      std::vector<Vec2> corners;
      for (const double x : {-hx, hx})
        for (const double y : {-hy, hy})
          for (const double z : {-hz, hz})
            corners.push_back(ground(pose.spatial * Eigen::Vector3d(x, y, z)));
      out_.polygons.push_back(convex_hull(std::move(corners)));
    } else if (kind == "cylinder" || kind == "sphere") {
      if (kind == "cylinder")
        check_known(shape, kCylinderChildren, file_);
      else
        check_known(shape, kSphereChildren, file_);
      const XMLElement* radius = io_detail::single_child(shape, "radius", file_);
      if (radius == nullptr) {
        throw InputError(file_, io_detail::where_of(shape), "<" + kind + "> lacks <radius>");
      }
      const double r = positive(radius, numbers(radius, 1, file_)[0], file_);
      const Eigen::Vector3d axis = pose.spatial.linear() * Eigen::Vector3d::UnitZ();
      if (!pose.tilted) {
        out_.circles.push_back(Circle{pose.planar.position, r});
        return;
      }
      const Eigen::Vector3d centre = pose.spatial.translation();
      if (kind == "sphere" || std::abs(axis.z()) >= 1.0 - 1e-12) {  // upright after all
        out_.circles.push_back(Circle{ground(centre), r});
        return;
      }
      // A cylinder on its side (or leaning): the shadow of its two end discs, each taken as the
      // 32-gon around it (its projection holds the disc's, so the footprint is never smaller).
      const XMLElement* length = io_detail::single_child(shape, "length", file_);
      if (length == nullptr)
        throw InputError(file_, io_detail::where_of(shape),
                         "<cylinder> lacks <length>, which a tilted cylinder's footprint needs");
      const double half = 0.5 * positive(length, numbers(length, 1, file_)[0], file_);
      const Eigen::Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
      constexpr int kSides = 32;
      const double outer = r / std::cos(kPi / kSides);
      std::vector<Vec2> pts;
      for (const double end : {-half, half})
        for (int k = 0; k < kSides; ++k) {
          const double a = 2.0 * kPi * k / kSides;
          pts.push_back(ground(centre + end * axis + outer * (std::cos(a) * u + std::sin(a) * v)));
        }
      out_.polygons.push_back(convex_hull(std::move(pts)));
    } else if (kind == "plane") {
      // The ground, unless it stands up: a vertical plane is a wall floornav cannot represent.
      if (const XMLElement* normal = shape->FirstChildElement("normal")) {
        const std::vector<double> n = numbers(normal, 3, file_);
        const Eigen::Vector3d up = pose.spatial.linear() * Eigen::Vector3d(n[0], n[1], n[2]);
        if (up.x() != 0.0 || up.y() != 0.0)
          out_.skipped.push_back(io_detail::where_of(shape) + ": model '" + owner +
                                 "': a <plane> that is not the ground (normal not 0 0 1)");
      } else if (pose.tilted) {
        out_.skipped.push_back(io_detail::where_of(shape) + ": model '" + owner +
                               "': a tilted <plane> (not the ground)");
      }
    } else if (kind != "empty") {
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
  check_known(sdf, kSdfChildren, file);
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
  if (world != nullptr) {
    check_known(world, kWorldChildren, file);
    // Beside a <world>, a model is no part of it: it would be left out.
    for (const XMLElement* m = sdf->FirstChildElement("model"); m != nullptr;
         m = m->NextSiblingElement("model"))
      out.skipped.push_back(io_detail::where_of(m) +
                            ": a <model> outside the <world> is not part of it");
  }
  // Things that move or that Gazebo places: never a fixed obstacle floornav could read.
  for (const XMLElement* e = scope->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string_view kind = e->Name();
    if (kind == "actor" && holds_collision(e))
      out.skipped.push_back(io_detail::where_of(e) +
                            ": an <actor> moves, so its collisions are not read");
    if (kind == "population")
      out.skipped.push_back(io_detail::where_of(e) +
                            ": a <population> (models Gazebo places at random) is not read");
  }

  // The saved state: a model's live pose (its <link> poses there are world-frame, not used).
  std::map<std::string, Frame> state_poses;
  if (world != nullptr) {
    for (const XMLElement* state = world->FirstChildElement("state"); state != nullptr;
         state = state->NextSiblingElement("state")) {
      for (const XMLElement* m = state->FirstChildElement("model"); m != nullptr;
           m = m->NextSiblingElement("model")) {
        const char* name = m->Attribute("name");
        const XMLElement* pose = io_detail::single_child(m, "pose", file);
        if (name != nullptr && pose != nullptr) state_poses[name] = parse_pose(pose, file);
        // A model scaled in the state has another size than its collisions say.
        if (const XMLElement* scale = m->FirstChildElement("scale")) {
          const std::vector<double> s = numbers(scale, 3, file);
          if (s[0] != 1.0 || s[1] != 1.0 || s[2] != 1.0)
            out.skipped.push_back(io_detail::where_of(scale) + ": model '" +
                                  (name != nullptr ? name : "") +
                                  "' is scaled in the <state>, which is not read");
        }
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
    reader.model(e, Frame{}, false, name,
                 state != state_poses.end() ? std::optional<Frame>(state->second) : std::nullopt);
  }
  return out;
}

}  // namespace floornav
