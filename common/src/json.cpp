#include "tactile/common/json.hpp"

#include <fmt/ranges.h>

#include <cmath>
#include <fstream>

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

}  // namespace tactile
