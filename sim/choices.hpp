// Names for closed sets of choices. Every such choice in a parameter struct (sim/, vector/,
// apps/render/) is an enum class with one table of {name, value} pairs declared beside it as
//   constexpr std::array<Choice<E>, N> choices(E);
// found by argument-dependent lookup. The scene reader (io/) parses names with it, and whatever
// writes a choice back (the CLI's options and summaries) prints with it, so each name is spelled
// in one place. It lives in sim/ because every stage with parameter structs already depends on
// sim/.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace wisp::sim {

template <class T>
struct Choice {
  const char* name;
  T value;
};

// The name of `value` in `table`; std::out_of_range for a value the table lacks (a cast gone
// wrong: every enumerator has its entry).
template <class Table, class T>
const char* choice_name(const Table& table, T value) {
  for (const auto& c : table)
    if (c.value == value) return c.name;
  throw std::out_of_range("choice_name: a value without a name");
}
template <class E>
const char* choice_name(E value) {
  return choice_name(choices(E{}), value);
}

// The value named `name` in `table`, or nothing.
template <class Table>
auto parse_choice(const Table& table, std::string_view name)
    -> std::optional<decltype(table[0].value)> {
  for (const auto& c : table)
    if (name == c.name) return c.value;
  return std::nullopt;
}
template <class E>
std::optional<E> parse_choice(std::string_view name) {
  return parse_choice(choices(E{}), name);
}

// Every name in `table`, in table order (for messages and command-line checks).
template <class Table>
std::vector<std::string> choice_names(const Table& table) {
  std::vector<std::string> names;
  for (const auto& c : table) names.emplace_back(c.name);
  return names;
}
template <class E>
std::vector<std::string> choice_names() {
  return choice_names(choices(E{}));
}

}  // namespace wisp::sim
