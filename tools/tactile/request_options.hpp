#pragma once
// Command-line options made from a request's option table (tactile/common/option_table.hpp):
// one CLI11 option per row, its help text, unit, range, choices and default from the row and
// the request's defaults, and its value checked by the same rule the Python module applies.

#include <CLI/CLI.hpp>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <fmt/ranges.h>

#include "own_options.hpp"
#include "tactile/common/option_table.hpp"

namespace tactile::cli {

// The text typed for `row` as the value the table takes; text that is not a number stays text,
// so that option_problem words its complaint ("takes a number").
template <typename R>
OptionValue value_from_text(const OptionRow<R>& row, const std::string& text) {
  if (row.kind == OptionKind::seed) {
    // Digits only: "-0", "1e3" and " 7" are not how a seed is written down.
    std::uint64_t u{};
    const char* end = text.data() + text.size();
    if (const auto [stop, error] = std::from_chars(text.data(), end, u);
        !text.empty() && text.find_first_not_of("0123456789") == std::string::npos &&
        error == std::errc() && stop == end) {
      return u;
    }
    return text;
  }
  if (row.kind == OptionKind::integer || row.kind == OptionKind::number) {
    std::int64_t i{};
    const char* end = text.data() + text.size();
    if (const auto [stop, error] = std::from_chars(text.data(), end, i);
        error == std::errc() && stop == end && !text.empty()) {
      return i;
    }
    double d{};
    if (CLI::detail::lexical_cast(text, d)) {
      // "1e3" or " 7" for a whole number: the number it says.
      if (std::isfinite(d) && d == std::trunc(d) && std::abs(d) < 9e15) {
        return static_cast<std::int64_t>(d);
      }
      return d;
    }
  }
  return text;
}

// What `--help` shows after the type: "2 to 5000", "{auto,paper,ridge-blob}".
template <typename R>
std::string validator_text(const OptionRow<R>& row) {
  if (row.kind == OptionKind::choice) return fmt::format("{{{}}}", fmt::join(row.choices, ","));
  if (row.kind == OptionKind::choice_list) {
    return fmt::format("{{{}}},...", fmt::join(row.choices, ","));
  }
  if (row.kind == OptionKind::seed) return "0 to 2^64 - 1";
  if (row.kind != OptionKind::integer && row.kind != OptionKind::number) return {};
  const bool low = std::isfinite(row.min), high = std::isfinite(row.max);
  if (low && high) return fmt::format("{} to {}", row.min, row.max);
  if (low) return fmt::format(">= {}", row.min);
  if (high) return fmt::format("<= {}", row.max);
  return {};
}

// The option's complaint about `text` in CLI11's words ("2 is not a whole number"); CLI11 puts
// the flag before it.
template <typename R>
CLI::Validator row_check(const OptionRow<R>& row) {
  return CLI::Validator(
      [row](std::string& text) -> std::string {
        const OptionValue value = value_from_text(row, text);
        if (std::holds_alternative<std::string>(value) &&
            (row.kind == OptionKind::integer || row.kind == OptionKind::number)) {
          return fmt::format("{} is not {}", text,
                             row.kind == OptionKind::integer ? "a whole number" : "a number");
        }
        std::string problem = option_problem(row, value);
        // The number as typed ("1e308"), not as printed back ("1e+308"): the person finds it.
        if (const auto* d = std::get_if<double>(&value)) {
          const std::string printed = fmt::format("{} ", *d);
          if (problem.rfind(printed, 0) == 0) problem.replace(0, printed.size() - 1, text);
        }
        return problem;
      },
      validator_text(row));
}

// What `--help` shows for the value: INT, FLOAT, NAME, PATH, or the row's own name for text.
template <typename R>
std::string type_name(const OptionRow<R>& row) {
  switch (row.kind) {
    case OptionKind::integer:
    case OptionKind::seed:
      return "INT";
    case OptionKind::number:
      return "FLOAT";
    case OptionKind::choice:
      return "NAME";
    case OptionKind::choice_list:
      return "NAMES";
    case OptionKind::path:
      return "PATH";
    case OptionKind::text:
      return std::string(row.metavar);
    case OptionKind::flag:
      return "BOOL";
  }
  return {};
}

// Adds every row of `table` to `sub`, writing into `*request`.
template <typename R>
void add_request_options(CLI::App& sub, const std::shared_ptr<R>& request,
                         const std::vector<OptionRow<R>>& table) {
  for (const auto& row : table) {
    std::string flag =
        row.positional ? std::string(row.metavar) : option_label(row.name, OptionSpelling::cli);
    if (!row.cli_alias.empty()) flag += "," + std::string(row.cli_alias);
    if (row.kind == OptionKind::flag) {
      sub.add_flag_function(
          flag,
          [request, row](std::int64_t) { set_option(*request, row, true, OptionSpelling::cli); },
          row.help);
      continue;
    }
    CLI::Option* option = sub.add_option_function<std::string>(
        flag,
        [request, row](const std::string& text) {
          set_option(*request, row, value_from_text(row, text), OptionSpelling::cli);
        },
        describe_option(row, false));
    option->check(row_check(row));
    if (row.positional || row.required) option->required();
    if (row.must_exist && row.folder) {
      option->check(CLI::ExistingDirectory);
    } else if (row.must_exist && row.positional) {
      option->check(CLI::ExistingPath);
    } else if (row.must_exist) {
      option->check(CLI::ExistingFile);
    }
    option->type_name(type_name(row));
  }
}

// A subcommand whose options are a request's table, and the request its callbacks share.
template <typename R>
OwnCommand<R> add_request_command(CLI::App& parent, const std::string& name,
                                  const std::string& help, const std::vector<OptionRow<R>>& table) {
  OwnCommand<R> command = add_own_command<R>(parent, name, help);
  add_request_options(*command.sub, command.opt, table);
  return command;
}

}  // namespace tactile::cli
