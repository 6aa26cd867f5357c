#pragma once
// An enum's names, written once as a table: to_string(), parsing a name, and the tools' lists
// of choices all read it.

#include <iterator>
#include <optional>
#include <string_view>
#include <type_traits>

namespace lightsampler {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

/// The enum a table of EnumName (an array or a span of them) names.
template <class Table>
using NamedEnum = std::remove_cvref_t<decltype(std::begin(std::declval<const Table&>())->value)>;

/// The name `table` gives `value`; "?" for a value it does not list.
template <class Table>
constexpr const char* name_of(const Table& table, NamedEnum<Table> value) {
  for (const auto& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

/// The value `table` names `name`; none for a name it does not list.
template <class Table>
constexpr std::optional<NamedEnum<Table>> value_of(const Table& table, std::string_view name) {
  for (const auto& entry : table)
    if (name == entry.name) return entry.value;
  return std::nullopt;
}

}  // namespace lightsampler
