#include "tactile/common/json.hpp"

#include <fmt/ranges.h>

#include <cmath>
#include <fstream>
#include <set>

#include "provenance_fields.hpp"

namespace tactile {

void JsonOrigin::fail(const std::string& what) const {
  throw FormatError(fmt::format("{}: {}", origin, what));
}

nlohmann::json parse_json(const JsonOrigin& at, const std::string& text) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse errors, and numbers beyond a double
    at.fail(fmt::format("not valid JSON ({})", e.what()));
  }
}

nlohmann::json read_json_object(const std::filesystem::path& path, const std::string& what) {
  const JsonOrigin at{path.string()};
  std::ifstream in(path);
  if (!in) at.fail(fmt::format("cannot open {}", what));
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    at.fail(fmt::format("not valid JSON ({})", e.what()));
  }
  if (!j.is_object()) at.fail("expected a JSON object");
  return j;
}

void json_only_keys(const JsonOrigin& at, const nlohmann::json& j, const std::string& where,
                    const std::set<std::string>& known) {
  if (!j.is_object()) at.fail(fmt::format("{} must be a JSON object, got {}", where, j.dump()));
  for (const auto& [key, value] : j.items()) {
    if (!known.contains(key)) {
      at.fail(
          fmt::format("{}: unknown field '{}' (known: {})", where, key, fmt::join(known, ", ")));
    }
  }
}

const nlohmann::json& json_required(const JsonOrigin& at, const nlohmann::json& j, const char* key,
                                    const std::string& where) {
  const auto it = j.find(key);
  if (it == j.end()) {
    at.fail(where.empty() ? fmt::format("missing field '{}'", key)
                          : fmt::format("{}: missing field '{}'", where, key));
  }
  return *it;
}

double json_number(const JsonOrigin& at, const nlohmann::json& v, const std::string& what) {
  if (!v.is_number()) at.fail(fmt::format("'{}' must be a number, got {}", what, v.dump()));
  const double x = v.get<double>();
  if (!std::isfinite(x)) at.fail(fmt::format("'{}' is not finite", what));
  return x;
}

std::int64_t json_integer(const JsonOrigin& at, const nlohmann::json& v, const std::string& what) {
  if (!v.is_number_integer()) {
    at.fail(fmt::format("'{}' must be an integer, got {}", what, v.dump()));
  }
  return v.get<std::int64_t>();
}

std::string json_string(const JsonOrigin& at, const nlohmann::json& v, const std::string& what) {
  if (!v.is_string() || v.get<std::string>().empty()) {
    at.fail(fmt::format("'{}' must be a non-empty string, got {}", what, v.dump()));
  }
  return v.get<std::string>();
}

nlohmann::json provenance_json(const Provenance& provenance) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& f : kProvenanceFields) j[f.name] = provenance.*f.field;
  return j;
}

Provenance read_provenance_json(const JsonOrigin& at, const nlohmann::json& j,
                                const std::string& where) {
  std::set<std::string> known;
  for (const auto& f : kProvenanceFields) {
    known.insert(f.name);
    if (f.former_name != nullptr) known.insert(f.former_name);
  }
  json_only_keys(at, j, where, known);
  Provenance p;
  for (const auto& f : kProvenanceFields) {
    // The current key, else the former one, else empty.
    for (const char* key : {f.name, f.former_name}) {
      if (key != nullptr && j.contains(key)) {
        p.*f.field = json_field<std::string>(j, key, at.origin);
        break;
      }
    }
  }
  return p;
}

}  // namespace tactile
