#pragma once
// Strict reading of YAML maps: every key must be known, every value of the right type and
// finite; errors name the file, the line and the dotted key. Private to the io library.

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "floornav/core/input_error.hpp"
#include "floornav/geometry/vec2.hpp"
#include "maps/text_parse.hpp"  // kMaxInputMagnitude

namespace floornav::io_detail {

/// Where a node came from, for error messages: "line 12: key", or the key alone for a missing
/// node.
std::string where_of(const YAML::Node& node, const std::string& key);

[[noreturn]] void fail(const std::string& file, const YAML::Node& node, const std::string& key,
                       const std::string& what);

double read_double(const std::string& file, const YAML::Node& node, const std::string& key);
std::int64_t read_int(const std::string& file, const YAML::Node& node, const std::string& key);
bool read_bool(const std::string& file, const YAML::Node& node, const std::string& key);
std::string read_string(const std::string& file, const YAML::Node& node, const std::string& key);
/// A sequence of exactly `n` numbers (n = 0: any length).
std::vector<double> read_numbers(const std::string& file, const YAML::Node& node,
                                 const std::string& key, std::size_t n);
Vec2 read_point(const std::string& file, const YAML::Node& node, const std::string& key);
std::vector<Vec2> read_points(const std::string& file, const YAML::Node& node,
                              const std::string& key);

/// A YAML map whose keys are checked off as they are read; `finish()` rejects the rest.
class MapReader {
 public:
  MapReader(std::string file, YAML::Node node, std::string path);

  bool has(const std::string& key) const;
  /// The child node (marks the key as known); an undefined node when absent.
  YAML::Node get(const std::string& key);
  /// The dotted path of `key` below this map.
  std::string path_of(const std::string& key) const;
  const std::string& file() const { return file_; }
  const YAML::Node& node() const { return node_; }
  /// Throws for the first key not read, with a suggestion when one is close.
  void finish() const;

  // The Archive interface used by the parameter structs' serialize().
  void operator()(const char* key, double& field, const char* /*doc*/);
  void operator()(const char* key, int& field, const char* /*doc*/);
  void operator()(const char* key, bool& field, const char* /*doc*/);
  void operator()(const char* key, std::uint64_t& field, const char* /*doc*/);
  /// An enumeration named by a string; `enum_names(E{})` (found by ADL) lists the names.
  template <class E>
  requires std::is_enum_v<E>
  void operator()(const char* key, E& field, const char* /*doc*/) {
    if (!has(key)) {
      known_.insert(key);
      return;
    }
    const YAML::Node n = get(key);
    const std::string text = read_string(file_, n, path_of(key));
    std::string expected;
    const auto names = enum_names(E{});
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i].second == text) {
        field = names[i].first;
        return;
      }
      expected += (i == 0                  ? ""
                   : i + 1 == names.size() ? " or "
                                           : ", ") +
                  std::string(names[i].second);
    }
    fail(file_, n, path_of(key), "unknown value '" + text + "' (expected " + expected + ")");
  }
  template <class T>
  void section(const char* key, T& sub) {
    if (!has(key)) return;
    MapReader r(file_, get(key), path_of(key));
    sub.serialize(r);
    r.finish();
  }

 private:
  std::string file_;
  YAML::Node node_;
  std::string path_;
  std::set<std::string> known_;
};

}  // namespace floornav::io_detail
