#pragma once
/// @file
/// The one exception type for bad user input: it says which file, where in it (a line or a
/// dotted key), and what is wrong. Thrown only at boundaries (loaders, validation); the CLI turns
/// it into exit status 2.

#include <stdexcept>
#include <string>
#include <utility>

namespace floornav {

struct InputError : std::runtime_error {
  InputError(std::string file_, std::string where_, std::string what_)
      : std::runtime_error(render(file_, where_, what_)),
        file(std::move(file_)),
        where(std::move(where_)),
        detail(std::move(what_)) {}

  std::string file;    ///< the file at fault ("" for a command-line value)
  std::string where;   ///< "line 12", "controller.kind", ...
  std::string detail;  ///< what is wrong, without the file and the place

 private:
  /// "file:where: what" on one line: control characters and bytes that are not UTF-8 are
  /// spelled as escapes (\n, \r, \xHH), whatever the input the message quotes held.
  static std::string render(const std::string& file, const std::string& where,
                            const std::string& what);
};

}  // namespace floornav
