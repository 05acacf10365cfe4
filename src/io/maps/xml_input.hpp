#pragma once
// tinyxml2 helpers for the world readers: loading with InputError, strict numeric attributes,
// line numbers. Private to the io library.

#include <tinyxml2.h>

#include <filesystem>
#include <string>

#include "floornav/core/input_error.hpp"
#include "io/maps/text_parse.hpp"

namespace floornav::io_detail {

/// "line N" of an element.
inline std::string where_of(const tinyxml2::XMLElement* e) {
  return "line " + std::to_string(e->GetLineNum());
}

/// Parses `path` into `doc`; throws InputError for a missing file or malformed XML.
inline void load_xml(const std::filesystem::path& path, tinyxml2::XMLDocument& doc) {
  const std::string file = path.string();
  const tinyxml2::XMLError err = doc.LoadFile(file.c_str());
  if (err == tinyxml2::XML_ERROR_FILE_NOT_FOUND ||
      err == tinyxml2::XML_ERROR_FILE_COULD_NOT_BE_OPENED ||
      err == tinyxml2::XML_ERROR_FILE_READ_ERROR) {
    throw InputError(file, "", "cannot open the file");
  }
  if (err != tinyxml2::XML_SUCCESS) {
    throw InputError(file, "line " + std::to_string(doc.ErrorLineNum()),
                     std::string("malformed XML: ") + doc.ErrorStr());
  }
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
