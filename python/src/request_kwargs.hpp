#pragma once
// Python keyword arguments made from a request's option table (tactile/common/option_table.hpp):
// the same names as the command line's flags (with underscores), the same ranges and choices,
// checked by the same rule and raised as ValueError in the same words, and a docstring listing
// every keyword with its unit, range and default.

#include <fmt/format.h>

#include <string>
#include <vector>

#include "bindings.hpp"
#include "tactile/common/option_table.hpp"

namespace tactile::python {

// `value` as the table takes it: None (unset), bool, int, float, or text (str or os.PathLike).
inline OptionValue option_value_of(const py::handle& value, OptionKind kind) {
  if (value.is_none()) return std::monostate{};
  if (py::isinstance<py::bool_>(value)) {
    // Python's bool is an int: True would pass as 1 without this.
    if (kind != OptionKind::flag) throw py::type_error("takes a number, name or path, not a bool");
    return value.cast<bool>();
  }
  if (py::isinstance<py::int_>(value)) {
    try {
      return value.cast<std::int64_t>();
    } catch (const py::cast_error&) {
      if (kind != OptionKind::seed) throw py::type_error("the number is too large");
    }
    // A seed beyond the signed range; beyond 2^64 - 1 (or below the signed range) its row
    // refuses the digits as given.
    try {
      return value.cast<std::uint64_t>();
    } catch (const py::cast_error&) {
      return py::str(value).cast<std::string>();
    }
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (kind == OptionKind::choice_list &&
      (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value))) {
    std::string joined;
    for (const auto& item : value) {
      if (!py::isinstance<py::str>(item)) throw py::type_error("takes a list of names");
      if (!joined.empty()) joined += ',';
      joined += item.cast<std::string>();
    }
    return joined;
  }
  if (kind == OptionKind::path && py::hasattr(value, "__fspath__")) {
    return py::module_::import("os").attr("fspath")(value).cast<std::string>();
  }
  throw py::type_error(fmt::format(
      "takes {}, not {}", kind == OptionKind::path ? "a str or path" : "a number or name",
      py::str(py::type::of(value).attr("__name__")).cast<std::string>()));
}

// `request` with every keyword of `kwargs` set through its row; an unknown keyword is a
// TypeError naming the closest known one, a bad value a ValueError (RequestError).
template <typename R>
void set_from_kwargs(R& request, const std::vector<OptionRow<R>>& table, const py::kwargs& kwargs,
                     const std::string& function) {
  std::vector<std::string> names;
  for (const auto& row : table)
    if (!row.positional && !row.required) names.emplace_back(row.name);
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::cast<std::string>(key);
    const OptionRow<R>* row = find_option(table, name);
    if (!row || row->positional || row->required) {
      const auto near = closest_name(name, names);
      throw py::type_error(fmt::format("{}() got an unexpected keyword argument '{}'{}", function,
                                       name,
                                       near ? fmt::format(" (did you mean '{}'?)", *near) : ""));
    }
    OptionValue v;
    try {
      v = option_value_of(value, row->kind);
    } catch (const py::type_error& e) {
      throw py::type_error(fmt::format("{}: {}", name, e.what()));
    }
    set_option(request, *row, v, OptionSpelling::python);
  }
}

// The keywords of `table` for a docstring, one per line: "rate_hz: Camera frame rate [...]".
template <typename R>
std::string kwargs_doc(const std::vector<OptionRow<R>>& table) {
  std::string doc;
  for (const auto& row : table) {
    if (row.positional || row.required) continue;
    std::string help = describe_option(row);
    for (char& c : help)
      if (c == '\n') c = ' ';
    doc += fmt::format("\n  {}: {}", row.name, help);
  }
  return doc;
}

// Defines NAME(args..., **kwargs) as `run`, its docstring `about` followed by the keywords of
// `table`. pybind11 copies the docstring while defining, so it need not outlive this call.
template <typename R, typename Run, typename... Args>
void def_with_kwargs(py::module_& m, const char* name, Run run,
                     const std::vector<OptionRow<R>>& table, const std::string& about,
                     const Args&... args) {
  const std::string doc = about + kwargs_doc(table);
  m.def(name, run, args..., doc.c_str());
}

}  // namespace tactile::python
