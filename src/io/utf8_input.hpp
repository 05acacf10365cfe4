#pragma once
// Text enters floornav as UTF-8 or not at all: scenario and agent files, --set values, map and
// scenario paths, batch sources. A byte that is not UTF-8 is an input error naming it (and its
// line and column), since every name and path is written to JSON later, which holds UTF-8 only.
// Private to the io library.

#include <filesystem>
#include <string>
#include <string_view>

namespace floornav::io_detail {

/// Throws InputError(file, "line L, column C", "byte 0xHH is not UTF-8 ...") for the first byte
/// of a text file's content that is not UTF-8 (comments included: a file is text or it is not).
void check_utf8_text(std::string_view text, const std::string& file);

/// The same for one value given outside a file (a --set, a --grid, a command-line path):
/// InputError(file, where, "byte 0xHH at position N is not UTF-8 ...").
void check_utf8_value(std::string_view text, const std::string& file, const std::string& where);

/// The same for a path that outputs will name: InputError(file, where, "the path ... holds byte
/// 0xHH, which is not UTF-8 ...").
void check_utf8_path(const std::filesystem::path& path, const std::string& file,
                     const std::string& where);

}  // namespace floornav::io_detail
