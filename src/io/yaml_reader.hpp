#pragma once
// Strict reading of YAML maps: every key must be known, every value of the right type and
// finite; errors name the file, the line and the dotted key. Private to the io library.

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "floornav/core/enum_names.hpp"
#include "floornav/core/input_error.hpp"
#include "floornav/core/param_fields.hpp"
#include "floornav/geometry/vec2.hpp"
#include "maps/text_parse.hpp"  // kMaxInputMagnitude, did_you_mean

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
/// A section switched by one word: on (true, yes) or off (false, no).
bool read_switch(const std::string& file, const YAML::Node& node, const std::string& key);
/// A sequence of exactly `n` numbers (n = 0: any length).
std::vector<double> read_numbers(const std::string& file, const YAML::Node& node,
                                 const std::string& key, std::size_t n);
Vec2 read_point(const std::string& file, const YAML::Node& node, const std::string& key);
std::vector<Vec2> read_points(const std::string& file, const YAML::Node& node,
                              const std::string& key);

/// A YAML map whose keys are checked off as they are read; `finish()` rejects the rest, with a
/// "did you mean" naming the closest key the section knows. A section may have layers: a fleet's
/// robot entry over the shared `robot:` section. A key is read from the first layer that has it;
/// `sub()` gives a key's maps in every layer, layered the same way.
class MapReader {
 public:
  MapReader(std::string file, YAML::Node node, std::string path);

  /// This reader with `node` (a mapping named `path`) as a further layer under the others.
  void add_layer(const YAML::Node& node, std::string path);

  /// Whether the key is given; also makes `key` known to the section (for "did you mean").
  bool has(const std::string& key);
  /// The child node (marks the key as known); an undefined node when absent.
  YAML::Node get(const std::string& key);
  /// The child node; when it is missing, throws "missing (`what`)", or, when the section holds an
  /// unknown key that looks like a misspelling of it, an error naming that key.
  YAML::Node require(const std::string& key, const std::string& what);
  /// The reader of the mapping under `key` in every layer that has one.
  MapReader sub(const std::string& key);
  /// The dotted path of `key` below this map (in the layer that gives it).
  std::string path_of(const std::string& key) const;
  const std::string& file() const { return file_; }
  const YAML::Node& node() const { return layers_.front().node; }
  /// Throws for the first key not read, with a suggestion when one is close.
  void finish() const;

  // The archive of visit_fields (core/param_fields.hpp): the parameter structs' fields.
  void operator()(const char* key, double& field, const char* /*doc*/);
  void operator()(const char* key, int& field, const char* /*doc*/);
  void operator()(const char* key, bool& field, const char* /*doc*/);
  void operator()(const char* key, std::uint64_t& field, const char* /*doc*/);
  /// An enumeration named by a string (core/enum_names.hpp).
  template <NamedEnum E>
  void operator()(const char* key, E& field, const char* /*doc*/) {
    if (!has(key)) return;
    const YAML::Node n = get(key);
    const std::string text = read_string(file_, n, path_of(key));
    const std::optional<E> value = parse_enum<E>(text);
    if (!value) {
      std::vector<std::string_view> names;
      for (const EnumName<E>& e : enum_names(E{})) names.push_back(e.name);
      fail(file_, n, path_of(key),
           "unknown value '" + text + "'" + did_you_mean(text, names) + " (expected " +
               enum_choices<E>() + ")");
    }
    field = *value;
  }
  /// A section's mapping; a section that can be switched off (it has `enabled`) may also be given
  /// as one word, `on` or `off` (`controller.safety: off`).
  template <class T>
  void section(const char* key, T& sub_struct) {
    if (!has(key)) return;
    if constexpr (requires { sub_struct.enabled = true; }) {
      const YAML::Node n = get(key);
      if (n.IsScalar()) {
        sub_struct.enabled = read_switch(file_, n, path_of(key));
        return;
      }
    }
    MapReader r = sub(key);
    visit_fields(sub_struct, r);
    r.finish();
  }

 private:
  struct Layer {
    YAML::Node node;
    std::string path;
  };
  MapReader(std::string file, std::vector<Layer> layers);
  /// The layer holding `key`, or nullptr.
  const Layer* layer_of(const std::string& key) const;
  /// The known key closest to `key` (edit distance <= 2), or "".
  std::string closest_known(const std::string& key) const;

  std::string file_;
  std::vector<Layer> layers_;
  std::set<std::string> known_;
};

/// A YAML text read as one document: `node` is the first document (null when there is none) and
/// `second` where a second one starts, if the text holds more (text after `...`, a `---`, or after
/// a closed flow collection). Instead of YAML::LoadAll, which in yaml-cpp 0.7 never returns on
/// some inputs (`[3, 2], 0`: the parser stops advancing and every call makes another empty
/// document, found by the fuzzer), the documents are counted by the parser, at most two.
/// Throws what yaml-cpp throws for invalid YAML.
struct OneDocument {
  YAML::Node node;
  std::optional<YAML::Mark> second;
};
OneDocument load_one_document(const std::string& text);

}  // namespace floornav::io_detail
