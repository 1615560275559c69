#pragma once
// Minimal CSV writing for exports: numbers and plain identifiers only, so no quoting is needed.

#include <filesystem>
#include <fstream>
#include <string>

namespace tactile::csv {

// Opens `path` for writing, throws std::runtime_error naming the path if it cannot.
// Writes `header` (comma-separated names) as the first line.
std::ofstream open_with_header(const std::filesystem::path& path, const std::string& header);

// Flushes and checks the stream; throws std::runtime_error naming `path` on a write failure
// (disk full), so a truncated export is never reported as success.
void finish(std::ofstream& out, const std::filesystem::path& path);

}  // namespace tactile::csv
