#pragma once
/// @file
/// UTF-8 well-formedness. Every text floornav reads ends up in JSON (summary.json, results.jsonl)
/// or in Python strings, both of which are UTF-8 only: text is checked where it enters, so that
/// a byte that is not UTF-8 is one clear error naming it, never a failure in a writer later.

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace floornav {

/// The length of the well-formed UTF-8 sequence of 2 to 4 bytes starting at `text[i]` (a lead
/// byte of 0x80 or above), or 0 when it is not one: a stray continuation byte, an overlong form,
/// a surrogate (U+D800..U+DFFF), a code point above U+10FFFF or a sequence cut short.
std::size_t utf8_sequence_length(std::string_view text, std::size_t i);

/// The offset of the first byte of `text` that does not start a well-formed UTF-8 character, or
/// nullopt when all of it is UTF-8.
std::optional<std::size_t> first_non_utf8(std::string_view text);

/// "byte 0xe9 is not UTF-8 (after 'caf')": the byte at `at` and a little of what comes before it
/// on its line, for an error message (InputError escapes what is not printable).
std::string describe_non_utf8(std::string_view text, std::size_t at);

/// Why text must be UTF-8, for the end of such a message.
inline constexpr const char* kWhyUtf8 =
    "floornav reads text as UTF-8 (names and paths are written to JSON, which holds nothing else)";

}  // namespace floornav
