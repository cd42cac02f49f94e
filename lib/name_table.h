#pragma once
/// @file
/// One way to name an enum: a table of (value, name) rows, written once beside the enum's
/// functions, and three lookups over it. Every enum the user types or reads by name (spline
/// kind, follower kind, engine cycle, run status, output format, spring ends, …) keeps its
/// table this way, so a new value is one row.

#include <cstddef>
#include <optional>
#include <string>

namespace needle {

/// A row of a name table.
template <typename E>
struct NameRow {
  E value;
  const char* name;
};

/// The name of `value` in `table`, or "?" when it has no row (a bug: every value has one).
template <typename E, std::size_t N>
const char* NameOf(const NameRow<E> (&table)[N], E value) {
  for (const NameRow<E>& row : table) {
    if (row.value == value) return row.name;
  }
  return "?";
}

/// The value named `name` in `table`, or nullopt.
template <typename E, std::size_t N>
std::optional<E> ValueOf(const NameRow<E> (&table)[N], const std::string& name) {
  for (const NameRow<E>& row : table) {
    if (name == row.name) return row.value;
  }
  return std::nullopt;
}

/// Every name of `table`, quoted or not, joined by `separator` ("a, b, c"; for messages).
template <typename E, std::size_t N>
std::string NameList(const NameRow<E> (&table)[N], const char* separator = ", ",
                     bool quoted = false) {
  std::string out;
  for (const NameRow<E>& row : table) {
    if (!out.empty()) out += separator;
    out += quoted ? "\"" + std::string(row.name) + "\"" : std::string(row.name);
  }
  return out;
}

/// The names as a choice for messages: "\"a\", \"b\" or \"c\"" (`quoted`), or "a, b or c".
template <typename E, std::size_t N>
std::string NameChoice(const NameRow<E> (&table)[N], bool quoted = true) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) {
    if (i > 0) out += i + 1 == N ? " or " : ", ";
    out += quoted ? "\"" + std::string(table[i].name) + "\"" : std::string(table[i].name);
  }
  return out;
}

}  // namespace needle
