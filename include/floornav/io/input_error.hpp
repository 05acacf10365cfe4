#pragma once
/// @file
/// The one exception type for bad user input: it says which file, where in it (a line or a
/// dotted key), and what is wrong. Thrown only at boundaries (loaders, validation); the CLI turns
/// it into exit status 2.

#include <stdexcept>
#include <string>

namespace floornav {

struct InputError : std::runtime_error {
  InputError(std::string file_, std::string where_, std::string what_)
      : std::runtime_error(render(file_, where_, what_)),
        file(std::move(file_)),
        where(std::move(where_)) {}

  std::string file;   ///< the file at fault ("" for a command-line value)
  std::string where;  ///< "line 12", "controller.kind", ...

 private:
  static std::string render(const std::string& file, const std::string& where,
                            const std::string& what) {
    std::string out = file.empty() ? std::string("<command line>") : file;
    if (!where.empty()) out += ":" + where;
    return out + ": " + what;
  }
};

}  // namespace floornav
