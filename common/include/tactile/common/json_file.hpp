#pragma once
// The strict first step of reading a small JSON file (models, calibrations, scenes).

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace tactile {

// The JSON object in `path`. Throws tactile::FormatError "<path>: cannot open <what>", "not valid
// JSON (...)" (also for a number beyond a double) or "expected a JSON object".
nlohmann::json read_json_object(const std::filesystem::path& path, const std::string& what);

}  // namespace tactile
