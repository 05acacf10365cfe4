#include "yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <limits>
#include <sstream>

#include <yaml-cpp/eventhandler.h>

#include <fmt/format.h>

namespace floornav::io_detail {

namespace {
std::string scalar_of(const std::string& file, const YAML::Node& node, const std::string& key,
                      const char* expected) {
  if (!node.IsDefined() || node.IsNull())
    fail(file, node, key, fmt::format("expected {}, got nothing", expected));
  if (!node.IsScalar())
    fail(file, node, key,
         fmt::format("expected {}, got a {}", expected, node.IsMap() ? "mapping" : "list"));
  return node.Scalar();
}
}  // namespace

std::string where_of(const YAML::Node& node, const std::string& key) {
  // A missing node has no place in the file: name the key alone. (Values given with --set are
  // blamed on their --set by load_scenario_text.)
  const auto mark = node.Mark();
  if (mark.line < 0) return key;
  const std::string line = fmt::format("line {}", mark.line + 1);
  return key.empty() ? line : line + ": " + key;
}

void fail(const std::string& file, const YAML::Node& node, const std::string& key,
          const std::string& what) {
  throw InputError(file, where_of(node, key), what);
}

double read_double(const std::string& file, const YAML::Node& node, const std::string& key) {
  const std::string s = scalar_of(file, node, key, "a number");
  double v = 0.0;
  const char* b = s.data();
  const char* e = s.data() + s.size();
  auto [ptr, ec] = std::from_chars(b, e, v);
  if (ec == std::errc::result_out_of_range)
    fail(file, node, key, fmt::format("{} is out of the range of a number", quote_input(s)));
  if (ec != std::errc() || ptr != e) {
    // YAML spellings of infinity and NaN are numbers, but never acceptable ones.
    const std::string lower = [&] {
      std::string t = s;
      std::transform(t.begin(), t.end(), t.begin(),
                     [](unsigned char c) { return std::tolower(c); });
      return t;
    }();
    if (lower == ".nan" || lower == ".inf" || lower == "-.inf" || lower == "+.inf")
      fail(file, node, key, fmt::format("'{}' is not a finite number", s));
    fail(file, node, key, fmt::format("expected a number, got {}", quote_input(s)));
  }
  if (!std::isfinite(v)) fail(file, node, key, fmt::format("'{}' is not a finite number", s));
  if (std::abs(v) > kMaxInputMagnitude)
    fail(file, node, key,
         fmt::format("{} is too large (more than 1e9 in magnitude)", quote_input(s)));
  return v;
}

std::int64_t read_int(const std::string& file, const YAML::Node& node, const std::string& key) {
  const std::string s = scalar_of(file, node, key, "a whole number");
  std::int64_t v = 0;
  auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec == std::errc::result_out_of_range && ptr == s.data() + s.size())
    fail(file, node, key, fmt::format("{} is out of the range of a whole number", quote_input(s)));
  if (ec != std::errc() || ptr != s.data() + s.size())
    fail(file, node, key, fmt::format("expected a whole number, got {}", quote_input(s)));
  return v;
}

bool read_bool(const std::string& file, const YAML::Node& node, const std::string& key) {
  const std::string s = scalar_of(file, node, key, "true or false");
  if (s == "true" || s == "True" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "False" || s == "no" || s == "off") return false;
  fail(file, node, key, fmt::format("expected true or false, got {}", quote_input(s)));
}

bool read_switch(const std::string& file, const YAML::Node& node, const std::string& key) {
  const std::string s = scalar_of(file, node, key, "on, off or a mapping of keys to values");
  if (s == "on" || s == "true" || s == "True" || s == "yes") return true;
  if (s == "off" || s == "false" || s == "False" || s == "no") return false;
  fail(file, node, key,
       fmt::format("expected on, off or a mapping of keys to values, got {}", quote_input(s)));
}

std::string read_string(const std::string& file, const YAML::Node& node, const std::string& key) {
  return scalar_of(file, node, key, "a string");
}

std::vector<double> read_numbers(const std::string& file, const YAML::Node& node,
                                 const std::string& key, std::size_t n) {
  if (!node.IsDefined())
    fail(file, node, key,
         n ? fmt::format("missing (expected a list of {} numbers)", n) : std::string("missing"));
  if (!node.IsSequence())
    fail(file, node, key,
         n ? fmt::format("expected a list of {} numbers", n) : std::string("expected a list"));
  if (n && node.size() != n)
    fail(file, node, key, fmt::format("expected {} numbers, got {}", n, node.size()));
  std::vector<double> out;
  for (std::size_t i = 0; i < node.size(); ++i)
    out.push_back(read_double(file, node[i], fmt::format("{}[{}]", key, i)));
  return out;
}

Vec2 read_point(const std::string& file, const YAML::Node& node, const std::string& key) {
  const auto v = read_numbers(file, node, key, 2);
  return {v[0], v[1]};
}

std::vector<Vec2> read_points(const std::string& file, const YAML::Node& node,
                              const std::string& key) {
  if (!node.IsSequence()) fail(file, node, key, "expected a list of [x, y] points");
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < node.size(); ++i)
    out.push_back(read_point(file, node[i], fmt::format("{}[{}]", key, i)));
  return out;
}

MapReader::MapReader(std::string file, YAML::Node node, std::string path)
    : MapReader(std::move(file), std::vector<Layer>{}) {
  add_layer(node, std::move(path));
}

MapReader::MapReader(std::string file, std::vector<Layer> layers)
    : file_(std::move(file)), layers_(std::move(layers)) {}

void MapReader::add_layer(const YAML::Node& node, std::string path) {
  if (!node.IsMap())
    fail(file_, node, path.empty() ? "(top level)" : path, "expected a mapping of keys to values");
  // yaml-cpp keeps both entries of a repeated key and returns the first: refuse the ambiguity.
  std::set<std::string> seen;
  for (const auto& kv : node) {
    if (kv.first.IsScalar() && !seen.insert(kv.first.Scalar()).second)
      fail(file_, kv.first, path.empty() ? kv.first.Scalar() : path + "." + kv.first.Scalar(),
           "given twice");
  }
  layers_.push_back({node, std::move(path)});
}

const MapReader::Layer* MapReader::layer_of(const std::string& key) const {
  for (const Layer& l : layers_) {
    const YAML::Node& n = l.node;  // const access: never inserts the key
    if (n[key].IsDefined()) return &l;
  }
  return nullptr;
}

bool MapReader::has(const std::string& key) {
  known_.insert(key);
  return layer_of(key) != nullptr;
}

YAML::Node MapReader::get(const std::string& key) {
  known_.insert(key);
  const Layer* l = layer_of(key);
  if (l == nullptr) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node& n = l->node;
  return n[key];
}

YAML::Node MapReader::require(const std::string& key, const std::string& what) {
  if (has(key)) return get(key);
  // A key of the section that is not known and is close to the missing one: a misspelling.
  for (const Layer& l : layers_)
    for (const auto& kv : l.node) {
      if (!kv.first.IsScalar() || known_.count(kv.first.Scalar())) continue;
      if (edit_distance(kv.first.Scalar(), key) <= 2)
        fail(
            file_, kv.first, l.path.empty() ? kv.first.Scalar() : l.path + "." + kv.first.Scalar(),
            fmt::format("unknown key (did you mean '{}'? it is required: {})", path_of(key), what));
    }
  fail(file_, node(), path_of(key), "missing (" + what + ")");
}

MapReader MapReader::sub(const std::string& key) {
  known_.insert(key);
  std::vector<Layer> layers;
  for (const Layer& l : layers_) {
    const YAML::Node& n = l.node;
    const YAML::Node child = n[key];
    if (!child.IsDefined()) continue;
    const std::string path = l.path.empty() ? key : l.path + "." + key;
    if (!child.IsMap()) {
      if (layers.empty()) fail(file_, child, path, "expected a mapping of keys to values");
      break;  // a value that is not a mapping hides the layers under it
    }
    layers.push_back({child, path});
  }
  if (layers.empty()) fail(file_, node(), path_of(key), "missing");
  MapReader out(file_, std::vector<Layer>{});
  for (Layer& l : layers) out.add_layer(l.node, std::move(l.path));
  return out;
}

std::string MapReader::path_of(const std::string& key) const {
  const Layer* l = layer_of(key);
  const std::string& path = (l != nullptr ? *l : layers_.front()).path;
  return path.empty() ? key : path + "." + key;
}

std::string MapReader::closest_known(const std::string& key) const {
  std::string hint;
  std::size_t best = 3;
  for (const std::string& k : known_) {
    const std::size_t d = edit_distance(key, k);
    if (d < best) best = d, hint = k;
  }
  return hint;
}

void MapReader::finish() const {
  for (const Layer& l : layers_)
    for (const auto& kv : l.node) {
      const auto path = [&](const std::string& k) { return l.path.empty() ? k : l.path + "." + k; };
      if (!kv.first.IsScalar()) fail(file_, kv.first, path("?"), "keys must be plain names");
      const std::string key = kv.first.Scalar();
      if (known_.count(key)) continue;
      if (key == "<<")  // yaml-cpp reads a merge key as a key like any other
        fail(file_, kv.first, l.path.empty() ? std::string("<<") : l.path,
             std::string("'<<' is a YAML merge key (`<<: *anchor`), which floornav does not read: "
                         "write the keys out") +
                 (l.path.rfind("robots[", 0) == 0
                      ? ", or give what the robots share once, in `robot:` beside `robots:`"
                      : " (an alias of a whole value, `key: *anchor`, does work)"));
      const std::string hint = closest_known(key);
      const std::string shown = key.size() > 80 ? key.substr(0, 80) + "..." : key;
      fail(file_, kv.first, path(shown),
           hint.empty() ? std::string("unknown key")
                        : fmt::format("unknown key (did you mean '{}'?)", path(hint)));
    }
}

void MapReader::operator()(const char* key, double& field, const char*) {
  if (has(key))
    field = read_double(file_, get(key), path_of(key));
  else
    known_.insert(key);
}
void MapReader::operator()(const char* key, int& field, const char*) {
  if (!has(key)) {
    known_.insert(key);
    return;
  }
  const auto v = read_int(file_, get(key), path_of(key));
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    fail(file_, get(key), path_of(key), "number too large");
  field = static_cast<int>(v);
}
void MapReader::operator()(const char* key, bool& field, const char*) {
  if (has(key))
    field = read_bool(file_, get(key), path_of(key));
  else
    known_.insert(key);
}
void MapReader::operator()(const char* key, std::uint64_t& field, const char*) {
  if (!has(key)) return;
  const YAML::Node n = get(key);
  const std::string s = scalar_of(file_, n, path_of(key), "a whole number");
  if (!s.empty() && s.front() == '-' && s.find_first_not_of("-0123456789") == std::string::npos)
    fail(file_, n, path_of(key), "must not be negative");
  std::uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec == std::errc::result_out_of_range && ptr == s.data() + s.size())
    fail(
        file_, n, path_of(key),
        fmt::format("{} is out of the range of a whole number (at most 2^64 - 1)", quote_input(s)));
  if (ec != std::errc() || ptr != s.data() + s.size())
    fail(file_, n, path_of(key), fmt::format("expected a whole number, got {}", quote_input(s)));
  field = v;
}

namespace {

/// Counts documents and keeps where the second starts; builds nothing.
class DocumentCounter : public YAML::EventHandler {
 public:
  void OnDocumentStart(const YAML::Mark& mark) override {
    if (++documents == 2) second = mark;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}

  int documents{0};
  std::optional<YAML::Mark> second;
};

}  // namespace

OneDocument load_one_document(const std::string& text) {
  OneDocument out;
  {
    std::istringstream in(text);
    YAML::Parser parser(in);
    DocumentCounter counter;
    // At most two calls: a parser that stops advancing returns true for ever.
    for (int call = 0; call < 2 && parser.HandleNextDocument(counter); ++call) {
    }
    out.second = counter.second;
  }
  if (!out.second) out.node = YAML::Load(text);
  return out;
}

}  // namespace floornav::io_detail
