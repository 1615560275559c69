#pragma once
// An operation's options as data: one table per request struct, kept beside the struct in the
// library that owns the operation. Each row names the option once (snake_case: the Python
// keyword; the command line's --flag is the same with dashes), says what it takes (a number in a
// range, a name from the enum's name table, a path) and how to put it into the request. The
// defaults are not in the table: they are the request struct's own member initialisers, read
// back from a default-constructed request for `--help` and the Python docstring. The command
// line and the Python module build their options from the table, so a range, a choice or a help
// text is written once and the front ends cannot disagree.

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "tactile/common/names.hpp"

namespace tactile {

// text: a name that is not a path or a choice (an address); path and text both refuse the empty
// string, so that a forgotten value is never taken as the current folder or as nothing at all.
// seed: a whole number from 0 to 2^64 - 1 exactly as typed (digits only), since a seed read
// through a double or a signed type would become another seed without a word.
// choice_list: names from the enum's table, comma-separated ("means,bands").
enum class OptionKind { integer, number, choice, path, text, flag, seed, choice_list };

// A value as a front end hands it over: unset (Python's None, for an option that is unset by
// default), a switch, a whole number (unsigned only beyond the signed range, for seeds), a
// number, or a name or path (text). The table's row turns it into the request's field.
using OptionValue =
    std::variant<std::monostate, bool, std::int64_t, double, std::string, std::uint64_t>;

// The words of every refused seed, after the value as typed.
inline constexpr std::string_view kSeedRule = "is not a whole number from 0 to 2^64 - 1";

// A usage error found in a request's values or in the rules between them (the command line's
// exit 2, Python's ValueError). The message names the option as the front end spells it when
// the front end gives its spelling (see option_label).
class RequestError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// How a front end spells an option: "--px-per-mm" or "px_per_mm".
enum class OptionSpelling { cli, python };
inline std::string option_label(std::string_view name, OptionSpelling spelling) {
  std::string label(name);
  if (spelling == OptionSpelling::python) return label;
  for (char& c : label)
    if (c == '_') c = '-';
  return "--" + label;
}

// "means,bands" as {"means", "bands"} (a choice_list's value).
inline std::vector<std::string> split_names(std::string_view text) {
  std::vector<std::string> names;
  for (std::size_t from = 0;;) {
    const std::size_t comma = text.find(',', from);
    names.emplace_back(text.substr(from, comma == std::string_view::npos ? comma : comma - from));
    if (comma == std::string_view::npos) return names;
    from = comma + 1;
  }
}

template <typename R>
struct OptionRow {
  std::string_view name;  // snake_case
  OptionKind kind = OptionKind::number;
  std::string help;
  std::string_view unit;  // "mm", "Hz", "px/mm"; empty for counts and names
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  std::vector<std::string> choices;  // OptionKind::choice: the accepted names, in table order
  bool positional = false;           // the command line's first argument (required)
  // A named option that must be given (--recordings DIR): a positional argument of the Python
  // function, not a keyword.
  bool required = false;
  std::string_view metavar;    // positional and text: its name in `--help`, e.g. IMAGE_DIR
  bool optional = false;       // the field may be unset (std::optional)
  std::string_view cli_alias;  // an older command-line spelling still taken, e.g. --strain
  bool must_exist = false;     // a path that must name an existing file or folder
  bool folder = false;         // with must_exist: a folder, not a file
  // OptionKind::path: what else is wrong with the text (empty: nothing), e.g. a name that is
  // neither a built-in layout nor a .json file.
  std::function<std::string(const std::string&)> check_text;
  // Numbers: a rule beyond the range (e.g. whole hertz), what is wrong in words or empty.
  std::function<std::string(double)> check_number;
  std::function<void(R&, const OptionValue&)> set;
  std::function<OptionValue(const R&)> get;
  // The value a default-constructed request holds, as text; empty when it is unset by default
  // (the operation then decides, as the help text says).
  std::function<std::string(const R&)> shown;
};

// Whether `v` passes `row`'s range, and if not, the rule in words ("from 2 to 5000", "> 0").
template <typename R>
std::string range_rule(const OptionRow<R>& row) {
  const bool low = std::isfinite(row.min), high = std::isfinite(row.max);
  if (low && high) return fmt::format("from {} to {}", row.min, row.max);
  if (low) return fmt::format(">= {}", row.min);
  if (high) return fmt::format("<= {}", row.max);
  return "finite";
}

// What is wrong with `value` for `row` (kind, range, choices), in words that follow the option's
// name ("0 is out of range: must be from 2 to 5000"); empty when it fits.
template <typename R>
std::string option_problem(const OptionRow<R>& row, const OptionValue& value) {
  if (std::holds_alternative<std::monostate>(value)) {
    return row.optional ? std::string() : std::string("cannot be unset (None)");
  }
  switch (row.kind) {
    case OptionKind::integer:
    case OptionKind::number: {
      double v = 0;
      if (const auto* i = std::get_if<std::int64_t>(&value)) {
        v = static_cast<double>(*i);
      } else if (const auto* d = std::get_if<double>(&value)) {
        if (row.kind == OptionKind::integer) return fmt::format("{} is not a whole number", *d);
        v = *d;
      } else {
        return row.kind == OptionKind::integer ? "takes a whole number" : "takes a number";
      }
      if (!std::isfinite(v)) return fmt::format("{} is not a finite number", v);
      if (row.check_number) return row.check_number(v);
      if (!(v >= row.min && v <= row.max)) {
        return fmt::format("{} is out of range: must be {}", v, range_rule(row));
      }
      return {};
    }
    case OptionKind::choice: {
      const auto* name = std::get_if<std::string>(&value);
      if (!name) return "takes a name";
      for (const auto& c : row.choices)
        if (c == *name) return {};
      return fmt::format("unknown value '{}' (known: {})", *name, fmt::join(row.choices, ", "));
    }
    case OptionKind::choice_list: {
      const auto* names = std::get_if<std::string>(&value);
      if (!names) return "takes names";
      if (names->empty()) return "is empty";
      for (const std::string& name : split_names(*names)) {
        if (std::find(row.choices.begin(), row.choices.end(), name) == row.choices.end()) {
          return fmt::format("unknown value '{}' (known: {})", name, fmt::join(row.choices, ", "));
        }
      }
      return {};
    }
    case OptionKind::path: {
      const auto* path = std::get_if<std::string>(&value);
      if (!path) return "takes a path";
      if (path->empty()) return "the path is empty";
      if (path->find('\0') != std::string::npos) return "the path holds a NUL character";
      return row.check_text ? row.check_text(*path) : std::string();
    }
    case OptionKind::text: {
      const auto* text = std::get_if<std::string>(&value);
      if (!text) return "takes text";
      if (text->empty()) return "is empty";
      return row.check_text ? row.check_text(*text) : std::string();
    }
    case OptionKind::flag:
      return std::holds_alternative<bool>(value) ? std::string() : "takes true or false";
    case OptionKind::seed:
      if (std::holds_alternative<std::uint64_t>(value)) return {};
      if (const auto* i = std::get_if<std::int64_t>(&value)) {
        return *i >= 0 ? std::string() : fmt::format("{} {}", *i, kSeedRule);
      }
      if (const auto* d = std::get_if<double>(&value)) return fmt::format("{} {}", *d, kSeedRule);
      if (const auto* text = std::get_if<std::string>(&value)) {
        return fmt::format("{} {}", *text, kSeedRule);
      }
      return "takes a whole number";
  }
  return {};
}

// Checks `value` (option_problem) and puts it into `request`; throws RequestError naming the
// option in the front end's spelling ("--px-per-mm: 0 is out of range: must be from 2 to 5000").
template <typename R>
void set_option(R& request, const OptionRow<R>& row, const OptionValue& value,
                OptionSpelling spelling) {
  if (const std::string problem = option_problem(row, value); !problem.empty()) {
    throw RequestError(fmt::format("{}: {}", option_label(row.name, spelling), problem));
  }
  row.set(request, value);
}

// Every field of `request` against its row, for a request filled in by a program rather than
// through set_option; throws RequestError naming the first bad one.
template <typename R>
void check_options(const R& request, const std::vector<OptionRow<R>>& table,
                   OptionSpelling spelling) {
  for (const auto& row : table) {
    if (const std::string problem = option_problem(row, row.get(request)); !problem.empty()) {
      throw RequestError(fmt::format("{}: {}", option_label(row.name, spelling), problem));
    }
  }
}

// As check_options, leaving out the front end's own arguments (positional and required rows: an
// input it has checked, or an object such as a movie passed instead of a file).
template <typename R>
void check_named_options(const R& request, const std::vector<OptionRow<R>>& table,
                         OptionSpelling spelling) {
  for (const auto& row : table) {
    if (row.positional || row.required) continue;
    if (const std::string problem = option_problem(row, row.get(request)); !problem.empty()) {
      throw RequestError(fmt::format("{}: {}", option_label(row.name, spelling), problem));
    }
  }
}

// The row named `name`, or nullptr.
template <typename R>
const OptionRow<R>* find_option(const std::vector<OptionRow<R>>& table, std::string_view name) {
  for (const auto& row : table)
    if (row.name == name) return &row;
  return nullptr;
}

// The closest of `candidates` to `word` by edit distance, when close enough to be a typo.
std::optional<std::string> closest_name(std::string_view word,
                                        const std::vector<std::string>& candidates);

namespace option_rows {

// The text of a field's value for `--help` (numbers as a person writes them; unset: empty).
inline std::string shown_value(bool v) {
  return v ? "on" : "off";
}
inline std::string shown_value(int v) {
  return std::to_string(v);
}
inline std::string shown_value(std::uint64_t v) {
  return std::to_string(v);
}
inline std::string shown_value(double v) {
  return fmt::format("{}", v);
}
inline std::string shown_value(const std::filesystem::path& v) {
  return v.string();
}
inline std::string shown_value(const std::string& v) {
  return v;
}
template <typename T>
std::string shown_value(const std::optional<T>& v) {
  return v ? shown_value(*v) : std::string();
}

inline OptionValue value_of(bool v) {
  return v;
}
inline OptionValue value_of(int v) {
  return std::int64_t{v};
}
inline OptionValue value_of(std::uint64_t v) {
  return v;
}
inline OptionValue value_of(double v) {
  return v;
}
inline OptionValue value_of(const std::filesystem::path& v) {
  return v.string();
}
inline OptionValue value_of(const std::string& v) {
  return v;
}
template <typename T>
OptionValue value_of(const std::optional<T>& v) {
  return v ? value_of(*v) : OptionValue{};
}

template <typename T>
struct field_type {
  using type = T;
};
template <typename T>
struct field_type<std::optional<T>> {
  using type = T;
};

// The field a row writes: a data member pointer (&Request::x_mm) or, for a field inside a member
// struct, a generic lambda from the request to a reference to it,
// `[](auto& r) -> auto& { return r.params.gain; }` (called on const requests too).
template <typename R, typename Field>
using field_of = std::remove_cvref_t<std::invoke_result_t<Field, R&>>;

// What every row begins with: its name, kind and help.
template <typename R>
OptionRow<R> new_row(std::string_view name, OptionKind kind, std::string help) {
  OptionRow<R> row;
  row.name = name;
  row.kind = kind;
  row.help = std::move(help);
  return row;
}

// get and shown for a field whose stored value is what the row reads and shows (value_of and
// shown_value know its type).
template <typename R, typename Field>
void read_as_stored(OptionRow<R>& row, Field field) {
  row.get = [field](const R& r) { return value_of(std::invoke(field, r)); };
  row.shown = [field](const R& r) { return shown_value(std::invoke(field, r)); };
}

// A row for an int or double field (or an optional one, unset by default).
template <typename R, typename Field>
OptionRow<R> number(std::string_view name, Field field, double min, double max,
                    std::string_view unit, std::string help) {
  using F = field_of<R, Field>;
  using T = typename field_type<F>::type;
  static_assert(std::is_same_v<T, int> || std::is_same_v<T, double>);
  OptionRow<R> row = new_row<R>(
      name, std::is_same_v<T, int> ? OptionKind::integer : OptionKind::number, std::move(help));
  row.unit = unit;
  row.min = min;
  row.max = max;
  row.optional = !std::is_same_v<F, T>;
  row.set = [field](R& r, const OptionValue& v) {
    if (std::holds_alternative<std::monostate>(v)) {
      if constexpr (!std::is_same_v<F, T>) std::invoke(field, r) = std::nullopt;
      return;
    }
    const double d = std::holds_alternative<double>(v)
                         ? std::get<double>(v)
                         : static_cast<double>(std::get<std::int64_t>(v));
    std::invoke(field, r) = static_cast<T>(d);
  };
  read_as_stored(row, field);
  return row;
}

// A row for an enum field (or an optional one, unset by default) named by its table.
template <typename R, typename Field, typename E, std::size_t N>
OptionRow<R> choice(std::string_view name, Field field, const std::array<Named<E>, N>& table,
                    std::string help) {
  using F = field_of<R, Field>;
  OptionRow<R> row = new_row<R>(name, OptionKind::choice, std::move(help));
  for (const auto& entry : table) row.choices.emplace_back(entry.name);
  row.optional = !std::is_same_v<F, E>;
  row.set = [field, table, name](R& r, const OptionValue& v) {
    if (std::holds_alternative<std::monostate>(v)) {
      if constexpr (!std::is_same_v<F, E>) std::invoke(field, r) = std::nullopt;
      return;
    }
    std::invoke(field, r) = parse_name(name, std::get<std::string>(v), table);
  };
  row.get = [field, table](const R& r) -> OptionValue {
    if constexpr (std::is_same_v<F, E>) {
      return name_in(table, std::invoke(field, r));
    } else {
      return std::invoke(field, r) ? OptionValue(name_in(table, *std::invoke(field, r)))
                                   : OptionValue{};
    }
  };
  row.shown = [field, table](const R& r) {
    if constexpr (std::is_same_v<F, E>) {
      return name_in(table, std::invoke(field, r));
    } else {
      return std::invoke(field, r) ? name_in(table, *std::invoke(field, r)) : std::string();
    }
  };
  return row;
}

// A row for a path field (std::filesystem::path or std::string, or an optional one, unset by
// default).
template <typename R, typename Field>
OptionRow<R> path(std::string_view name, Field field, std::string help) {
  using F = field_of<R, Field>;
  using T = typename field_type<F>::type;
  OptionRow<R> row = new_row<R>(name, OptionKind::path, std::move(help));
  row.optional = !std::is_same_v<F, T>;
  row.set = [field](R& r, const OptionValue& v) {
    if (std::holds_alternative<std::monostate>(v)) {
      if constexpr (!std::is_same_v<F, T>) std::invoke(field, r) = std::nullopt;
      return;
    }
    std::invoke(field, r) = T(std::get<std::string>(v));
  };
  read_as_stored(row, field);
  return row;
}

// A row for a switch (a bool field, off by default: the command line's flag without a value).
template <typename R, typename Field>
OptionRow<R> flag(std::string_view name, Field field, std::string help) {
  static_assert(std::is_same_v<field_of<R, Field>, bool>);
  OptionRow<R> row = new_row<R>(name, OptionKind::flag, std::move(help));
  row.set = [field](R& r, const OptionValue& v) { std::invoke(field, r) = std::get<bool>(v); };
  read_as_stored(row, field);
  return row;
}

// A row for a list of names from an enum's table (a std::vector<E> field, empty by default: the
// operation decides, as the help says).
template <typename R, typename Field, typename E, std::size_t N>
OptionRow<R> choice_list(std::string_view name, Field field, const std::array<Named<E>, N>& table,
                         std::string help) {
  static_assert(std::is_same_v<field_of<R, Field>, std::vector<E>>);
  OptionRow<R> row = new_row<R>(name, OptionKind::choice_list, std::move(help));
  for (const auto& entry : table) row.choices.emplace_back(entry.name);
  row.optional = true;
  row.set = [field, table, name](R& r, const OptionValue& v) {
    auto& list = std::invoke(field, r);
    list.clear();
    if (std::holds_alternative<std::monostate>(v)) return;
    for (const std::string& each : split_names(std::get<std::string>(v))) {
      list.push_back(parse_name(name, each, table));
    }
  };
  const auto text = [field, table](const R& r) {
    std::string joined;
    for (const E e : std::invoke(field, r)) {
      if (!joined.empty()) joined += ',';
      joined += name_in(table, e);
    }
    return joined;
  };
  row.get = [text](const R& r) -> OptionValue {
    std::string joined = text(r);
    return joined.empty() ? OptionValue{} : OptionValue(std::move(joined));
  };
  row.shown = text;
  return row;
}

// A row for a random seed (a std::uint64_t field, or an optional one unset by default): the
// whole range, no rounding, no wrapping.
template <typename R, typename Field>
OptionRow<R> seed(std::string_view name, Field field, std::string help) {
  using F = field_of<R, Field>;
  static_assert(std::is_same_v<typename field_type<F>::type, std::uint64_t>);
  OptionRow<R> row = new_row<R>(name, OptionKind::seed, std::move(help));
  row.optional = !std::is_same_v<F, std::uint64_t>;
  row.set = [field](R& r, const OptionValue& v) {
    if (std::holds_alternative<std::monostate>(v)) {
      if constexpr (!std::is_same_v<F, std::uint64_t>) std::invoke(field, r) = std::nullopt;
      return;
    }
    if (const auto* u = std::get_if<std::uint64_t>(&v)) {
      std::invoke(field, r) = *u;
    } else {
      std::invoke(field, r) = static_cast<std::uint64_t>(std::get<std::int64_t>(v));
    }
  };
  read_as_stored(row, field);
  return row;
}

// A row for text that is neither a path nor a choice (an optional std::string field), shown in
// `--help` as `metavar`; `check` says what else is wrong with it (empty: nothing).
template <typename R, typename Field>
OptionRow<R> text(std::string_view name, Field field, std::string_view metavar,
                  std::function<std::string(const std::string&)> check, std::string help) {
  OptionRow<R> row = path<R>(name, field, std::move(help));
  row.kind = OptionKind::text;
  row.metavar = metavar;
  row.check_text = std::move(check);
  return row;
}

// The command line's first argument, a path.
template <typename R>
OptionRow<R> positional_path(std::string_view name, std::filesystem::path R::*field,
                             std::string_view metavar, std::string help) {
  OptionRow<R> row = path<R>(name, field, std::move(help));
  row.positional = true;
  row.metavar = metavar;
  row.must_exist = true;
  return row;
}

// A path option naming a file that must exist (a calibration, a model).
template <typename R, typename Field>
OptionRow<R> existing_path(std::string_view name, Field field, std::string help) {
  OptionRow<R> row = path<R>(name, field, std::move(help));
  row.must_exist = true;
  return row;
}

// `row` of an inner request (e.g. capture's) as a row of an outer one that holds it, reached by
// `access` (a generic lambda to a reference, as for the builders): a request built from others
// takes their options with their help, ranges and defaults, written once.
template <typename Outer, typename Inner, typename Access>
OptionRow<Outer> nested(const OptionRow<Inner>& row, Access access) {
  OptionRow<Outer> out;
  out.name = row.name;
  out.kind = row.kind;
  out.help = row.help;
  out.unit = row.unit;
  out.min = row.min;
  out.max = row.max;
  out.choices = row.choices;
  out.positional = row.positional;
  out.metavar = row.metavar;
  out.optional = row.optional;
  out.must_exist = row.must_exist;
  out.folder = row.folder;
  out.required = row.required;
  out.cli_alias = row.cli_alias;
  out.check_text = row.check_text;
  out.check_number = row.check_number;
  out.set = [set = row.set, access](Outer& o, const OptionValue& v) {
    set(std::invoke(access, o), v);
  };
  out.get = [get = row.get, access](const Outer& o) { return get(std::invoke(access, o)); };
  out.shown = [shown = row.shown, access](const Outer& o) { return shown(std::invoke(access, o)); };
  return out;
}

// The rows of `table` named in `names`, in that order, as rows of Outer (nested). Throws
// std::logic_error for a name the table does not have: a table is the program's own.
template <typename Outer, typename Inner, typename Access>
void append_nested(std::vector<OptionRow<Outer>>& out, const std::vector<OptionRow<Inner>>& table,
                   Access access, std::initializer_list<std::string_view> names) {
  for (const std::string_view name : names) {
    const OptionRow<Inner>* row = find_option(table, name);
    if (!row) throw std::logic_error(fmt::format("no option '{}' to take over", name));
    out.push_back(nested<Outer>(*row, access));
  }
}

}  // namespace option_rows

// Text for a row in `--help` and the Python docstring: its help, unit, range or choices (unless
// the front end shows them itself) and the default, e.g. "Camera frame rate [Hz; from 1 to
// 100000; default 60]".
template <typename R>
std::string describe_option(const OptionRow<R>& row, bool with_range = true) {
  std::vector<std::string> facts;
  if (!row.unit.empty()) facts.emplace_back(row.unit);
  if (with_range && (row.kind == OptionKind::integer || row.kind == OptionKind::number)) {
    if (std::isfinite(row.min) || std::isfinite(row.max)) facts.push_back(range_rule(row));
  }
  if (with_range && row.kind == OptionKind::seed) facts.emplace_back("from 0 to 2^64 - 1");
  if (with_range && (row.kind == OptionKind::choice || row.kind == OptionKind::choice_list)) {
    facts.push_back(fmt::format("{}", fmt::join(row.choices, " | ")));
  }
  if (!row.positional) {
    const std::string shown = row.shown(R{});
    if (!shown.empty()) facts.push_back("default " + shown);
  }
  if (facts.empty()) return row.help;
  return fmt::format("{} [{}]", row.help, fmt::join(facts, "; "));
}

}  // namespace tactile
