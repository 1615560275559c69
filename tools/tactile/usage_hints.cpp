#include "usage_hints.hpp"

#include <fmt/format.h>

#include <cctype>

#include "tactile/common/option_table.hpp"

namespace tactile::cli {

const CLI::App* find_command(const CLI::App& parent, const std::string& word) {
  for (const CLI::App* sub : parent.get_subcommands({})) {
    if (sub->check_name(word)) return sub;
  }
  return nullptr;
}

std::vector<std::string> command_names(const CLI::App& parent) {
  std::vector<std::string> names;
  for (const CLI::App* sub : parent.get_subcommands({})) names.push_back(sub->get_name());
  return names;
}

CommandPath command_path(const CLI::App& app, int argc, char** argv) {
  CommandPath path;
  const CLI::App* at = &app;
  for (int i = 1; i < argc; ++i) {
    const CLI::App* sub = find_command(*at, argv[i]);
    if (!sub) break;
    at = sub;
    path.command = sub;
    path.name += (path.name.empty() ? "" : " ") + sub->get_name();
    path.first_argument = i + 1;
  }
  return path;
}

std::optional<std::string> unknown_flag(const CommandPath& path, int argc, char** argv) {
  if (!path.command) return std::nullopt;
  std::vector<std::string> known;
  for (const CLI::Option* option : path.command->get_options()) {
    for (const auto& name : option->get_lnames()) known.push_back("--" + name);
  }
  for (int i = path.first_argument; i < argc; ++i) {
    std::string word = argv[i];
    if (word == "--") break;  // what follows is positional
    // A flag is "--name" (or "--name=value"); "-1" and "-0.5" are values.
    if (word.size() < 3 || word.rfind("--", 0) != 0 ||
        !std::isalpha(static_cast<unsigned char>(word[2]))) {
      continue;
    }
    word = word.substr(0, word.find('='));
    if (word == "--help" || path.command->get_option_no_throw(word) != nullptr) continue;
    const auto near = closest_name(word, known);
    return fmt::format("unknown option '{}' for `tactile {}`{}", word, path.name,
                       near ? fmt::format(" (did you mean '{}'?)", *near) : "");
  }
  return std::nullopt;
}

void refuse_empty_values(CLI::App& app) {
  const CLI::Validator not_empty(
      [](const std::string& text) {
        return text.empty() ? std::string("is empty") : std::string();
      },
      "");
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_size() > 0) option->check(not_empty);
  }
  for (CLI::App* sub : app.get_subcommands({})) refuse_empty_values(*sub);
}

}  // namespace tactile::cli
