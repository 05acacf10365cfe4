#pragma once
// tinyxml2 helpers for the world readers: loading with InputError, strict numeric attributes,
// line numbers. Private to the io library.

#include <tinyxml2.h>

#include <algorithm>
#include <filesystem>
#include <initializer_list>
#include <string>
#include <string_view>

#include "floornav/core/input_error.hpp"
#include "io/input_file.hpp"
#include "io/maps/text_parse.hpp"
#include "io/utf8_input.hpp"

namespace floornav::io_detail {

/// "line N" of an element.
inline std::string where_of(const tinyxml2::XMLElement* e) {
  return "line " + std::to_string(e->GetLineNum());
}

/// Parses `path` into `doc`; throws InputError for a missing file (or one that is not a file, or
/// larger than kMaxXmlBytes) or malformed XML.
inline void load_xml(const std::filesystem::path& path, tinyxml2::XMLDocument& doc) {
  const std::string file = path.string();
  const std::string text = read_input_file(path, "XML world", kMaxXmlBytes);
  check_utf8_text(text, file);
  const tinyxml2::XMLError err = doc.Parse(text.data(), text.size());
  if (err != tinyxml2::XML_SUCCESS) {
    throw InputError(file, "line " + std::to_string(doc.ErrorLineNum()),
                     std::string("malformed XML: ") + doc.ErrorStr());
  }
}

/// Throws for the first child element of `parent` not named in `allowed` (a typo such as
/// `<obstcle>` would otherwise drop what it holds without a word), with a "did you mean".
inline void check_children(const tinyxml2::XMLElement* parent,
                           std::initializer_list<std::string_view> allowed,
                           const std::string& file) {
  for (const tinyxml2::XMLElement* e = parent->FirstChildElement(); e != nullptr;
       e = e->NextSiblingElement()) {
    const std::string_view name = e->Name();
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
    std::string expected;
    for (std::string_view a : allowed)
      expected += (expected.empty() ? "<" : ", <") + std::string(a) + ">";
    throw InputError(file, where_of(e),
                     "unknown element <" + std::string(name.substr(0, 64)) + "> in <" +
                         parent->Name() + ">" + did_you_mean(name, allowed) + "; expected " +
                         expected);
  }
}

/// The one child element `name` of `parent`, or nullptr; a second one is an error (which of the
/// two was meant?).
inline const tinyxml2::XMLElement* single_child(const tinyxml2::XMLElement* parent,
                                                const char* name, const std::string& file) {
  const tinyxml2::XMLElement* e = parent->FirstChildElement(name);
  if (e != nullptr && e->NextSiblingElement(name) != nullptr) {
    throw InputError(file, where_of(e->NextSiblingElement(name)),
                     std::string("<") + parent->Name() + "> has more than one <" + name + ">");
  }
  return e;
}

/// The finite number in attribute `name` of `e`; throws InputError if missing or not a number.
inline double number_attribute(const tinyxml2::XMLElement* e, const char* name,
                               const std::string& file) {
  const char* text = e->Attribute(name);
  if (text == nullptr) {
    throw InputError(file, where_of(e),
                     std::string("<") + e->Name() + "> lacks the attribute '" + name + "'");
  }
  const auto v = parse_double(text);
  if (!v) {
    throw InputError(file, where_of(e),
                     std::string("<") + e->Name() + " " + name + "=\"" + text +
                         "\">: " + magnitude_problem(text).value_or("expected a finite number"));
  }
  return *v;
}

}  // namespace floornav::io_detail
