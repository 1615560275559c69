#pragma once
// The project's one strict JSON reader (calibration, scenes, pore models, layouts, experiments,
// model files): every problem becomes tactile::FormatError "<origin>: <what is wrong>", never a
// stray nlohmann exception, and numbers are checked for what a person meant (finite, whole).

#include <fmt/format.h>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <type_traits>
#include <utility>

#include "tactile/common/error.hpp"
#include "tactile/common/provenance.hpp"

namespace tactile {

// Where a document came from (a file name, or a description): the prefix of every message.
struct JsonOrigin {
  std::string origin;
  [[noreturn]] void fail(const std::string& what) const;
};

// `text` parsed; "not valid JSON (...)" also for a number beyond a double.
nlohmann::json parse_json(const JsonOrigin& at, const std::string& text);

// The text of a JSON file that its parser checks itself: "<path>: cannot open <what>".
std::string read_json_text(const std::filesystem::path& path, const std::string& what);

// The JSON object in `path`: "<path>: cannot open <what>", "not valid JSON (...)" or
// "expected a JSON object".
nlohmann::json read_json_object(const std::filesystem::path& path, const std::string& what);

// read_json_object of a file that names its own format: also "<path>: 'format' is not <format>".
nlohmann::json read_json_of_format(const std::filesystem::path& path, const std::string& what,
                                   const std::string& format);

// `j` is an object whose keys are all in `known`: "<where> must be a JSON object, got ..." or
// "<where>: unknown field 'k' (known: ...)".
void json_only_keys(const JsonOrigin& at, const nlohmann::json& j, const std::string& where,
                    const std::set<std::string>& known);

// j[key]: "<where>: missing field '<key>'" (or without "<where>: " when `where` is empty).
const nlohmann::json& json_required(const JsonOrigin& at, const nlohmann::json& j, const char* key,
                                    const std::string& where);

// A finite number: "'<what>' must be a number, got ..." or "'<what>' is not finite".
double json_number(const JsonOrigin& at, const nlohmann::json& v, const std::string& what);

// A whole number: "'<what>' must be an integer, got ...".
std::int64_t json_integer(const JsonOrigin& at, const nlohmann::json& v, const std::string& what);

// A non-empty string: "'<what>' must be a non-empty string, got ...".
std::string json_string(const JsonOrigin& at, const nlohmann::json& v, const std::string& what);

// j[name] as T, for fields whose type says it all: "<where>: field '<name>' is missing / has
// the wrong type"; an integer field also "must be a whole number from MIN to MAX, got ..." (a
// fraction, or a number beyond T, which nlohmann would convert with undefined behaviour).
template <typename T>
T json_field(const nlohmann::json& j, const char* name, const std::string& where) {
  if (!j.is_object() || !j.contains(name)) {
    throw FormatError(fmt::format("{}: field '{}' is missing", where, name));
  }
  if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
    const nlohmann::json& v = j.at(name);
    if (v.is_number()) {
      const bool fits = v.is_number_unsigned()  ? std::in_range<T>(v.get<std::uint64_t>())
                        : v.is_number_integer() ? std::in_range<T>(v.get<std::int64_t>())
                                                : false;
      if (!fits) {
        throw FormatError(fmt::format("{}: field '{}' must be a whole number from {} to {}, got {}",
                                      where, name, std::numeric_limits<T>::min(),
                                      std::numeric_limits<T>::max(), v.dump()));
      }
    }
  }
  try {
    return j.at(name).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw FormatError(fmt::format("{}: field '{}' has the wrong type", where, name));
  }
}

// A provenance as a JSON object of its six fields, named as the struct's.
nlohmann::json provenance_json(const Provenance& provenance);
// Reads one back: every key optional (absent reads as empty), strings only, no unknown key
// ("<where>: unknown field ..."). Objects written before the six names held source,
// mapping_method and mapping_parameters_json, read as input, method and parameters_json.
Provenance read_provenance_json(const JsonOrigin& at, const nlohmann::json& j,
                                const std::string& where);

}  // namespace tactile
