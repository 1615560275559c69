#pragma once
// The shapes of the options that a command owns itself, for the commands (and benchmarks) whose
// options are not a library request's table: a subcommand with its options struct, an input
// that must exist, a number in a range whose `--help` shows its default. Each shape is written
// here once so that every command checks and words it alike.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <memory>
#include <string>
#include <type_traits>

#include "number_checks.hpp"

namespace tactile::cli {

// A subcommand and the options (or request) its callbacks share, held by a shared pointer since
// the callbacks outlive the function that declares them.
template <typename Options>
struct OwnCommand {
  std::shared_ptr<Options> opt;
  CLI::App* sub;
};

template <typename Options>
OwnCommand<Options> add_own_command(CLI::App& parent, const std::string& name,
                                    const std::string& help) {
  return {std::make_shared<Options>(), parent.add_subcommand(name, help)};
}

// A required input: a file, or a folder, that exists when the command line is read.
inline CLI::Option* add_input_file(CLI::App& sub, const std::string& name,
                                   std::filesystem::path& field, const std::string& help) {
  return sub.add_option(name, field, help)->required()->check(CLI::ExistingFile);
}
inline CLI::Option* add_input_folder(CLI::App& sub, const std::string& name,
                                     std::filesystem::path& field, const std::string& help) {
  return sub.add_option(name, field, help)->required()->check(CLI::ExistingDirectory);
}

// A number from `min` to `max` (both included) that shows its default in `--help`. The text is
// checked as a wide signed number (or a double), not as the field's own type: "70000" for a
// 16-bit port must read "out of range", not "not a whole number".
template <typename T>
CLI::Option* add_ranged(CLI::App& sub, const std::string& flag, T& field, const std::string& help,
                        std::type_identity_t<T> min, std::type_identity_t<T> max) {
  using Checked = std::conditional_t<std::is_integral_v<T>, long long, double>;
  return sub.add_option(flag, field, help)->check(within<Checked>(min, max))->capture_default_str();
}

}  // namespace tactile::cli
