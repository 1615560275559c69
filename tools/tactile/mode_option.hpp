#pragma once
// A command-line option whose value is one of an enum's names: the command line is where the
// string enters, so it is turned into the enum here and the work never sees the name.

#include <CLI/CLI.hpp>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "tactile/common/names.hpp"

namespace tactile::cli {

template <typename E, std::size_t N>
CLI::Option* add_mode_option(CLI::App& sub, const std::string& flag, E& target,
                             const std::array<Named<E>, N>& table, const std::string& description) {
  std::vector<std::string> names;
  for (const auto& entry : table) names.emplace_back(entry.name);
  return sub
      .add_option_function<std::string>(
          flag,
          [&target, table, flag](const std::string& name) {
            target = parse_name(flag, name, table);
          },
          description)
      ->check(CLI::IsMember(names))
      ->default_str(name_in(table, target));
}

}  // namespace tactile::cli
