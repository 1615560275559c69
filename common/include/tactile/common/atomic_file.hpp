#pragma once
// Small files (models, calibrations, scenes) written so that a failed write never destroys a
// file that was already there.

#include <filesystem>
#include <string>

namespace tactile {

// `text` written to NAME.partial and renamed over `path`. Throws std::runtime_error naming the
// file.
void write_file_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace tactile
