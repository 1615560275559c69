#pragma once
// Command-line options whose values are an enum's names: the command line is where the string
// enters, so it is turned into the enum here and the work never sees the name. The accepted
// names (and so `--help` and the message for a wrong one) come from the enum's one name table.

#include <CLI/CLI.hpp>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "tactile/common/names.hpp"

namespace tactile::cli {

// On/off switches that also take `auto` (add_mode_option_or_auto with std::optional<bool>).
inline constexpr std::array<Named<bool>, 2> kOnOffNames = {{{true, "on"}, {false, "off"}}};

template <typename E, std::size_t N>
std::vector<std::string> table_names(const std::array<Named<E>, N>& table) {
  std::vector<std::string> names;
  for (const auto& entry : table) names.emplace_back(entry.name);
  return names;
}

// `target` (an E or a std::optional<E>) set from the name given; only the table's names pass.
template <typename Target, typename E, std::size_t N>
CLI::Option* add_parsed_option(CLI::App& sub, const std::string& flag, Target& target,
                               const std::array<Named<E>, N>& table,
                               const std::string& description) {
  return sub
      .add_option_function<std::string>(
          flag,
          [&target, table, flag](const std::string& name) {
            target = parse_name(flag, name, table);
          },
          description)
      ->check(CLI::IsMember(table_names(table)));
}

template <typename E, std::size_t N>
CLI::Option* add_mode_option(CLI::App& sub, const std::string& flag, E& target,
                             const std::array<Named<E>, N>& table, const std::string& description) {
  return add_parsed_option(sub, flag, target, table, description)
      ->default_str(name_in(table, target));
}

// A mode that stays unset unless given (the work then applies its own default).
template <typename E, std::size_t N>
CLI::Option* add_optional_mode_option(CLI::App& sub, const std::string& flag,
                                      std::optional<E>& target,
                                      const std::array<Named<E>, N>& table,
                                      const std::string& description) {
  return add_parsed_option(sub, flag, target, table, description);
}

// A mode that may also be `auto` (the default, listed first), left unset for the work to choose.
template <typename E, std::size_t N>
CLI::Option* add_mode_option_or_auto(CLI::App& sub, const std::string& flag,
                                     std::optional<E>& target, const std::array<Named<E>, N>& table,
                                     const std::string& description) {
  std::vector<std::string> names = {"auto"};
  for (auto& name : table_names(table)) names.push_back(std::move(name));
  return sub
      .add_option_function<std::string>(
          flag,
          [&target, table, flag](const std::string& name) {
            if (name == "auto") {
              target.reset();
            } else {
              target = parse_name(flag, name, table);
            }
          },
          description)
      ->check(CLI::IsMember(names))
      ->default_str("auto");
}

// A comma-separated list of modes, e.g. --inputs means,bands (empty unless given).
template <typename E, std::size_t N>
CLI::Option* add_mode_list_option(CLI::App& sub, const std::string& flag, std::vector<E>& target,
                                  const std::array<Named<E>, N>& table,
                                  const std::string& description) {
  return sub
      .add_option_function<std::vector<std::string>>(
          flag,
          [&target, table, flag](const std::vector<std::string>& names) {
            target.clear();
            for (const auto& name : names) target.push_back(parse_name(flag, name, table));
          },
          description)
      ->delimiter(',')
      ->check(CLI::IsMember(table_names(table)));
}

}  // namespace tactile::cli
