#pragma once
// JSON documents on disk for the capture module's small files (model, calibration, scene):
// atomic writes and a strict first step of reading.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tactile/common/atomic_file.hpp"

namespace tactile::capture {

using tactile::write_file_atomically;

// The JSON object in `path`. Throws tactile::FormatError "<path>: cannot open <what>", "not valid
// JSON (...)" (also for a number beyond a double) or "expected a JSON object".
nlohmann::json read_json_object(const std::filesystem::path& path, const std::string& what);

}  // namespace tactile::capture
