#pragma once
// Strict reading of one field of a JSON object, for the capture module's file readers.

#include <fmt/format.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tactile/common/error.hpp"

namespace tactile::capture {

// j[name] as T; FormatError "<where>: field '<name>' is missing / has the wrong type".
template <typename T>
T json_field(const nlohmann::json& j, const char* name, const std::string& where) {
  if (!j.is_object() || !j.contains(name)) {
    throw FormatError(fmt::format("{}: field '{}' is missing", where, name));
  }
  try {
    return j.at(name).get<T>();
  } catch (const nlohmann::json::exception&) {
    throw FormatError(fmt::format("{}: field '{}' has the wrong type", where, name));
  }
}

}  // namespace tactile::capture
