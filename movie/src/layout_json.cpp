// Custom layouts from JSON: a strict reader (every field required, nothing unknown accepted).

#include "tactile/movie/layout_json.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <set>

#include "tactile/common/error.hpp"
#include "tactile/common/json.hpp"
#include "tactile/common/plain_name.hpp"
#include "tactile/common/value_checks.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::movie {
namespace {

using nlohmann::json;

const json& field(const json& j, const char* name, const std::string& where) {
  return json_required(JsonOrigin{where}, j, name, "");
}

double number(const json& v, const std::string& what, const std::string& where) {
  return json_number(JsonOrigin{where}, v, what);
}

// A size in mm: from a micrometre to a metre; beyond either it is a unit mix-up or damage.
double size_mm(const json& v, const std::string& what, const std::string& where) {
  return checks::in_range(number(v, what, where), kMinLayoutSizeMm, kMaxLayoutSizeMm, where, what);
}

std::int32_t count(const json& v, const char* what, const std::string& where) {
  const auto n = json_integer(JsonOrigin{where}, v, what);
  // 256 x 256 is far beyond any pin array built; it also keeps rows * cols in range.
  if (n < 1 || n > 256) {
    throw FormatError(
        fmt::format("{}: '{}' = {} leaves the grid empty or absurd (1..256)", where, what, n));
  }
  return static_cast<std::int32_t>(n);
}

std::pair<double, double> pair_of(const json& v, const char* what, const std::string& where) {
  if (!v.is_array() || v.size() != 2) {
    throw FormatError(
        fmt::format("{}: '{}' must be an array of two numbers, got {}", where, what, v.dump()));
  }
  return {number(v[0], fmt::format("{}[0]", what), where),
          number(v[1], fmt::format("{}[1]", what), where)};
}

}  // namespace

Layout parse_layout_json(const std::string& text, const std::string& where) {
  const json j = parse_json(JsonOrigin{where}, text);
  if (!j.is_object()) throw FormatError(fmt::format("{}: a layout must be a JSON object", where));
  static const std::set<std::string> known = {"name",
                                              "rows",
                                              "cols",
                                              "pitch_mm",
                                              "contactor_size_mm",
                                              "deflection_axis",
                                              "deflection_range_um",
                                              "max_rate_hz"};
  for (const auto& [key, value] : j.items()) {
    if (!known.contains(key)) {
      throw FormatError(fmt::format(
          "{}: unknown field '{}' (known: name, rows, cols, pitch_mm, contactor_size_mm, "
          "deflection_axis, deflection_range_um, max_rate_hz)",
          where, key));
    }
  }
  Layout l;
  const auto& name = field(j, "name", where);
  if (!name.is_string() || name.get<std::string>().empty()) {
    throw FormatError(fmt::format("{}: 'name' must be a non-empty string", where));
  }
  l.name = name.get<std::string>();
  // Experiments name their movies, plots and perception tables after the layout.
  if (const auto error = plain_name_error("name", l.name))
    throw FormatError(fmt::format("{}: {}", where, *error));
  l.rows = count(field(j, "rows", where), "rows", where);
  l.cols = count(field(j, "cols", where), "cols", where);
  const auto pitch = field(j, "pitch_mm", where);
  pair_of(pitch, "pitch_mm", where);
  l.pitch_x_mm = size_mm(pitch[0], "pitch_mm[0] (x)", where);
  l.pitch_y_mm = size_mm(pitch[1], "pitch_mm[1] (y)", where);
  const auto size = field(j, "contactor_size_mm", where);
  pair_of(size, "contactor_size_mm", where);
  l.contactor_width_mm = size_mm(size[0], "contactor_size_mm[0] (width)", where);
  l.contactor_height_mm = size_mm(size[1], "contactor_size_mm[1] (height)", where);
  // Contactors wider than their pitch would overlap their neighbours: a unit mix-up (um for mm).
  if (l.contactor_width_mm > l.pitch_x_mm || l.contactor_height_mm > l.pitch_y_mm) {
    throw FormatError(fmt::format(
        "{}: contactor_size_mm [{}, {}] is larger than pitch_mm [{}, {}] (contactors would "
        "overlap)",
        where, l.contactor_width_mm, l.contactor_height_mm, l.pitch_x_mm, l.pitch_y_mm));
  }
  const auto& axis = field(j, "deflection_axis", where);
  try {
    if (!axis.is_string()) throw std::invalid_argument("not a name");
    l.axis = parse_name("deflection_axis", axis.get<std::string>(), kDeflectionAxisNames);
  } catch (const std::invalid_argument&) {
    throw FormatError(fmt::format("{}: 'deflection_axis' must be \"{}\", got {}", where,
                                  fmt::join(names_of(values_of(kDeflectionAxisNames)), "\" or \""),
                                  axis.dump()));
  }
  const auto [lo, hi] =
      pair_of(field(j, "deflection_range_um", where), "deflection_range_um", where);
  checks::in_range(lo, -1e6, 1e6, where, "deflection_range_um[0]");
  checks::in_range(hi, -1e6, 1e6, where, "deflection_range_um[1]");
  if (!(lo < hi)) {
    throw FormatError(fmt::format(
        "{}: 'deflection_range_um' [{}, {}] is empty (min must be below max)", where, lo, hi));
  }
  // Neutral (0) is where the firmware parks contactors and where every movie starts.
  if (!(lo <= 0 && hi >= 0)) {
    throw FormatError(
        fmt::format("{}: 'deflection_range_um' [{}, {}] does not contain 0 (the neutral position)",
                    where, lo, hi));
  }
  l.deflection_min_um = lo;
  l.deflection_max_um = hi;
  l.max_rate_hz = checks::in_range(number(field(j, "max_rate_hz", where), "max_rate_hz", where), 1,
                                   kMaxMovieRateHz, where, "max_rate_hz");
  return l;
}

Layout read_layout_json(const std::filesystem::path& path) {
  return parse_layout_json(read_json_text(path, "layout file"), path.string());
}

std::string layout_to_json(const Layout& l) {
  json j;
  j["name"] = l.name;
  j["rows"] = l.rows;
  j["cols"] = l.cols;
  j["pitch_mm"] = {l.pitch_x_mm, l.pitch_y_mm};
  j["contactor_size_mm"] = {l.contactor_width_mm, l.contactor_height_mm};
  j["deflection_axis"] = to_string(l.axis);
  j["deflection_range_um"] = {l.deflection_min_um, l.deflection_max_um};
  j["max_rate_hz"] = l.max_rate_hz;
  return j.dump(2);
}

Layout resolve_layout(const std::string& name_or_path) {
  if (std::filesystem::path(name_or_path).extension() == ".json") {
    return read_layout_json(name_or_path);
  }
  return layout_by_name(name_or_path);
}

}  // namespace tactile::movie
