#pragma once
// Modes travel through the libraries as enums; their names exist only where a string enters
// (command line, experiment file, model file) or leaves (files, messages). Each enum has one
// table of its values and names; `to_string`, its parser and the list of its values all come
// from that table, so a name is spelled once and every parser words its error the same.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace tactile {

template <typename E>
struct Named {
  E value;
  std::string_view name;
};

// The values of a table, in its order (for loops over every mode).
template <typename E, std::size_t N>
constexpr std::array<E, N> values_of(const std::array<Named<E>, N>& table) {
  std::array<E, N> values{};
  for (std::size_t i = 0; i < N; ++i) values[i] = table[i].value;
  return values;
}

template <typename E, std::size_t N>
std::string name_in(const std::array<Named<E>, N>& table, E value) {
  for (const auto& [v, name] : table)
    if (v == value) return std::string(name);
  return "(unnamed " + std::to_string(static_cast<long long>(value)) + ")";
}

// The names of `values`, in order (for messages and lists of accepted names); `to_string` of
// each is found by argument-dependent lookup.
template <typename Range>
std::vector<std::string> names_of(const Range& values) {
  std::vector<std::string> names;
  for (const auto e : values) names.emplace_back(to_string(e));
  return names;
}

// Throws std::invalid_argument naming `what`, the bad name and the accepted ones.
template <typename E, std::size_t N>
E parse_name(std::string_view what, std::string_view name, const std::array<Named<E>, N>& table) {
  std::vector<std::string> known;
  for (const auto& [value, n] : table) {
    if (n == name) return value;
    known.emplace_back(n);
  }
  throw std::invalid_argument(
      fmt::format("unknown {} '{}' (known: {})", what, name, fmt::join(known, ", ")));
}

}  // namespace tactile
