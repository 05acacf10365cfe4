#pragma once
/// @file
/// One mechanism for an enumeration's names (in files, outputs and Python): each enumeration `E`
/// that is written or read as text declares, next to it,
///
///     constexpr std::span<const EnumName<E>> enum_names(E);   // found by ADL
///
/// over a constexpr table that lists every enumerator once. `to_string`, `parse_enum` and
/// `enum_choices` work on any such enumeration, so no enumeration has its own switch.

#include <iterator>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace floornav {

/// One enumerator and its name.
template <class E>
struct EnumName {
  E value;
  std::string_view name;
};

/// An enumeration with a name table (`enum_names(E{})`, found by ADL).
template <class E>
concept NamedEnum = std::is_enum_v<E> && requires(E e) {
  { enum_names(e) } -> std::convertible_to<std::span<const EnumName<E>>>;
};

/// The name of `value` ("unknown" for a value outside the table: a cast integer).
template <NamedEnum E>
constexpr std::string_view to_string(E value) {
  for (const EnumName<E>& n : enum_names(E{}))
    if (n.value == value) return n.name;
  return "unknown";
}

/// The enumerator called `name`, or nullopt.
template <NamedEnum E>
constexpr std::optional<E> parse_enum(std::string_view name) {
  for (const EnumName<E>& n : enum_names(E{}))
    if (n.name == name) return n.value;
  return std::nullopt;
}

/// "a, b or c": the names of `items` (`name_of(item)`), for messages.
template <class Items, class NameOf>
std::string list_choices(const Items& items, NameOf name_of) {
  std::string out;
  std::size_t i = 0;
  for (const auto& item : items) {
    if (i > 0) out += i + 1 == std::size(items) ? " or " : ", ";
    out += name_of(item);
    ++i;
  }
  return out;
}

/// The enumeration's names for a message: "a, b or c".
template <NamedEnum E>
std::string enum_choices() {
  return list_choices(enum_names(E{}), [](const EnumName<E>& n) { return n.name; });
}

}  // namespace floornav
