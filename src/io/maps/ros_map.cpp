#include "floornav/io/ros_map.hpp"

#include <fmt/format.h>
#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/angle.hpp"
#include "io/input_file.hpp"
#include "io/maps/raster_image.hpp"
#include "io/maps/text_parse.hpp"
#include "io/utf8_input.hpp"
#include "io/yaml_reader.hpp"

namespace floornav {
namespace {

enum class MapMode { Trinary, Scale, Raw };

/// What a map_server yaml says.
struct RosMapMeta {
  std::filesystem::path image;
  double resolution{0.0};
  Pose2 origin;
  bool negate{false};
  double occupied_thresh{0.65};
  double free_thresh{0.196};
  MapMode mode{MapMode::Trinary};
};

/// Typed access to the top-level keys of a yaml map, with errors naming the line (or the key
/// when it is missing).
class YamlKeys {
 public:
  YamlKeys(const YAML::Node& root, std::string file) : root_(root), file_(std::move(file)) {}

  YAML::Node require(const std::string& key) const {
    const YAML::Node n = root_[key];
    if (!n || n.IsNull()) throw InputError(file_, key, "missing key '" + key + "'");
    return n;
  }

  bool has(const std::string& key) const {
    const YAML::Node n = root_[key];
    return n && !n.IsNull();
  }

  std::string where(const YAML::Node& n, const std::string& key) const {
    const YAML::Mark m = n.Mark();
    return m.is_null() ? key : "line " + std::to_string(m.line + 1);
  }

  [[noreturn]] void fail(const YAML::Node& n, const std::string& key,
                         const std::string& what) const {
    throw InputError(file_, where(n, key), key + ": " + what);
  }

  double number(const YAML::Node& n, const std::string& key) const {
    if (!n.IsScalar()) fail(n, key, "expected a number, got a " + kind(n));
    const auto v = io_detail::parse_double(n.Scalar());
    if (!v) {
      fail(n, key,
           io_detail::magnitude_problem(n.Scalar())
               .value_or("expected a finite number, got '" + n.Scalar() + "'"));
    }
    return *v;
  }

  double number(const std::string& key) const { return number(require(key), key); }

  std::string text(const std::string& key) const {
    const YAML::Node n = require(key);
    if (!n.IsScalar()) fail(n, key, "expected a string, got a " + kind(n));
    return n.Scalar();
  }

 private:
  static std::string kind(const YAML::Node& n) {
    if (n.IsSequence()) return "list";
    if (n.IsMap()) return "map";
    return "null";
  }

  YAML::Node root_;
  std::string file_;
};

// The map yaml's one document (bad YAML, a second document: InputError at its line).
YAML::Node parse_map_yaml(const std::string& text, const std::string& file) {
  YAML::Node root;
  try {
    const io_detail::OneDocument doc = io_detail::load_one_document(text);
    if (doc.second)
      throw InputError(file, "line " + std::to_string(doc.second->line + 1),
                       "a second YAML document: a map yaml is one document");
    root.reset(doc.node);
  } catch (const YAML::DeepRecursion& e) {
    throw InputError(file, e.mark.is_null() ? "" : "line " + std::to_string(e.mark.line + 1),
                     "invalid YAML: nested too deeply");
  } catch (const YAML::Exception& e) {
    throw InputError(file, e.mark.is_null() ? "" : "line " + std::to_string(e.mark.line + 1),
                     "invalid YAML: " + e.msg);
  }
  return root;
}

// Every key once, and only map_server's.
void check_map_keys(const YAML::Node& root, const YamlKeys& keys) {
  // yaml-cpp keeps both entries of a repeated key and returns the first: refuse the ambiguity.
  std::set<std::string> seen;
  for (const auto& kv : root) {
    if (kv.first.IsScalar() && !seen.insert(kv.first.Scalar()).second)
      keys.fail(kv.first, kv.first.Scalar(), "given twice");
  }

  // Every key of map_server's format; any other (a typo such as `negative:`) is an error.
  for (const auto& kv : root) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : std::string("?");
    const std::initializer_list<std::string_view> kKeys = {
        "image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"};
    if (std::find(kKeys.begin(), kKeys.end(), key) == kKeys.end())
      keys.fail(kv.first, key.substr(0, 64),
                "unknown key" + io_detail::did_you_mean(key, kKeys) +
                    " (a map_server yaml has image, resolution, origin, negate, occupied_thresh, "
                    "free_thresh and mode)");
  }
}

Pose2 read_origin(const YamlKeys& keys) {
  const YAML::Node origin = keys.require("origin");
  if (!origin.IsSequence() || origin.size() != 3) {
    keys.fail(origin, "origin", "expected a list [x, y, yaw]");
  }
  const double yaw = keys.number(origin[2], "origin");
  if (std::abs(yaw) > 2.0 * kPi + 1e-9)
    keys.fail(origin[2], "origin",
              fmt::format("yaw {:.6g} is beyond +-2 pi: angles are in radians (if you meant {:.6g} "
                          "degrees, write {:.6g})",
                          yaw, yaw, deg_to_rad(yaw)));
  return Pose2{{keys.number(origin[0], "origin"), keys.number(origin[1], "origin")},
               wrap_angle(yaw)};
}

// map_server reads negate as 0 or 1 (ROS 2: also a boolean); 2 is a typo, not "true".
bool read_negate(const YamlKeys& keys) {
  const YAML::Node negate = keys.require("negate");
  if (!negate.IsScalar()) keys.fail(negate, "negate", "expected 0, 1, true or false");
  const std::string n = std::string(io_detail::trim(negate.Scalar()));
  if (n == "1" || n == "true" || n == "True" || n == "TRUE") return true;
  if (n == "0" || n == "false" || n == "False" || n == "FALSE") return false;
  keys.fail(negate, "negate",
            "expected 0, 1, true or false, got " + io_detail::quote_input(negate.Scalar()));
}

void read_thresholds(const YamlKeys& keys, RosMapMeta& meta) {
  for (const char* key : {"occupied_thresh", "free_thresh"}) {
    const YAML::Node n = keys.require(key);
    const double v = keys.number(n, key);
    if (v < 0.0 || v > 1.0) keys.fail(n, key, "must be in [0, 1], got " + n.Scalar());
    (std::string(key) == "free_thresh" ? meta.free_thresh : meta.occupied_thresh) = v;
  }
  if (meta.free_thresh > meta.occupied_thresh) {
    // A pixel between the two would be both free and occupied.
    keys.fail(keys.require("free_thresh"), "free_thresh",
              fmt::format("must not be above occupied_thresh ({:.6g}), got {}",
                          meta.occupied_thresh, keys.require("free_thresh").Scalar()));
  }
}

MapMode read_mode(const YamlKeys& keys) {
  if (keys.has("mode")) {
    const std::string mode = keys.text("mode");
    if (mode == "trinary") return MapMode::Trinary;
    if (mode == "scale") return MapMode::Scale;
    if (mode == "raw") return MapMode::Raw;
    keys.fail(keys.require("mode"), "mode",
              "unknown mode '" + mode + "' (expected trinary, scale or raw)");
  }
  return RosMapMeta{}.mode;  // map_server's default
}

RosMapMeta read_meta(const std::filesystem::path& yaml) {
  const std::string file = yaml.string();
  const std::string text =
      io_detail::read_input_file(yaml, "ROS map yaml", io_detail::kMaxMapYamlBytes);
  io_detail::check_utf8_text(text, file);
  const YAML::Node root = parse_map_yaml(text, file);
  if (!root.IsMap()) throw InputError(file, "", "expected a YAML map of map_server keys");
  const YamlKeys keys(root, file);
  check_map_keys(root, keys);

  RosMapMeta meta;
  const std::string image = keys.text("image");
  if (io_detail::trim(image).empty()) keys.fail(keys.require("image"), "image", "is empty");
  meta.image = image;
  if (meta.image.is_relative()) meta.image = yaml.parent_path() / meta.image;

  const YAML::Node res = keys.require("resolution");
  meta.resolution = keys.number(res, "resolution");
  if (!(meta.resolution > 0.0))
    keys.fail(res, "resolution", "must be positive, got " + res.Scalar());
  meta.origin = read_origin(keys);
  meta.negate = read_negate(keys);
  read_thresholds(keys, meta);
  meta.mode = read_mode(keys);

  if (auto problem =
          io_detail::input_file_problem(meta.image, "map image", io_detail::kMaxImageBytes)) {
    keys.fail(keys.require("image"), "image",
              "image file '" + meta.image.string() + "' " + *problem);
  }
  return meta;
}

/// Classifies every pixel as map_server does and flips the rows (image row 0 is the top).
OccupancyGrid to_grid(const io_detail::RasterImage& img, const RosMapMeta& m,
                      const RosMapOptions& options) {
  const std::uint8_t unknown = options.unknown == UnknownPolicy::Occupied ? 1 : 0;
  std::vector<std::uint8_t> occ(static_cast<std::size_t>(img.width) * img.height);
  // Which cells were unknown, for pictures (OccupancyGrid::set_unknown); the simulator sees them
  // as the policy says.
  std::vector<std::uint8_t> unknown_cells(occ.size(), 0);
  bool any_unknown = false;
  for (int j = 0; j < img.height; ++j) {
    std::uint8_t* row = occ.data() + static_cast<std::size_t>(img.height - 1 - j) * img.width;
    for (int i = 0; i < img.width; ++i) {
      double v = img.mean(i, j);
      if (m.negate) v = 255.0 - v;
      double p = 0.0;
      if (m.mode == MapMode::Raw) {
        // ROS 1 stores the (truncated) value itself: 0..100 is a percentage, the rest unknown.
        const double value = std::floor(v);
        if (value > 100.0) {
          row[i] = unknown;
          unknown_cells[static_cast<std::size_t>(row - occ.data()) + i] = 1;
          any_unknown = true;
          continue;
        }
        p = value / 100.0;
      } else {
        // Trinary and scale agree on a binary grid: scale's in-between values (1..99) are
        // neither known free nor known occupied, so they follow the unknown policy too.
        p = (255.0 - v) / 255.0;
      }
      row[i] = p > m.occupied_thresh ? 1 : (p < m.free_thresh ? 0 : unknown);
      if (!(p > m.occupied_thresh) && !(p < m.free_thresh)) {
        unknown_cells[static_cast<std::size_t>(row - occ.data()) + i] = 1;
        any_unknown = true;
      }
    }
  }
  OccupancyGrid grid(img.width, img.height, m.resolution, m.origin, std::move(occ));
  if (any_unknown) grid.set_unknown(std::move(unknown_cells));
  return grid;
}

}  // namespace

OccupancyGrid load_ros_map(const std::filesystem::path& yaml, const RosMapOptions& options,
                           std::filesystem::path* image_read) {
  const RosMapMeta meta = read_meta(yaml);
  if (image_read != nullptr) *image_read = meta.image;
  return to_grid(io_detail::read_raster_image(meta.image), meta, options);
}

OccupancyGrid load_ros_image_map(const std::filesystem::path& image, double resolution,
                                 const RosMapOptions& options) {
  if (!(resolution > 0.0) || !std::isfinite(resolution)) {
    throw InputError(image.string(), "resolution",
                     fmt::format("must be a positive finite number, got {:.6g}", resolution));
  }
  RosMapMeta meta;  // map_server's defaults
  meta.image = image;
  meta.resolution = resolution;
  return to_grid(io_detail::read_raster_image(image), meta, options);
}

}  // namespace floornav
