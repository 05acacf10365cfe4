#pragma once
/// @file
/// An output that could not be written (a read-only folder, a full disk): the path and the
/// operating system's reason. An InputError (the same one-line message, file = the path), so that
/// code that reports input errors reports it too; the CLI tells the two apart: exit status 1 for
/// this one, 2 for bad input.

#include "floornav/core/input_error.hpp"

namespace floornav {

struct OutputError : InputError {
  OutputError(std::string path, std::string what)
      : InputError(std::move(path), "", std::move(what)) {}
};

}  // namespace floornav
