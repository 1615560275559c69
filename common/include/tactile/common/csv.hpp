#pragma once
// Minimal CSV writing for exports: numbers and plain identifiers only, so no quoting is needed.

#include <filesystem>
#include <string>

#include "tactile/common/atomic_write.hpp"

namespace tactile::csv {

// A CSV file being written atomically (see atomic_write.hpp): nothing appears at `path` until
// finish(). Throws std::runtime_error naming the path and the OS's reason if its folder cannot
// take a file. Writes `header` (comma-separated names) as the first line.
AtomicOstream open_with_header(const std::filesystem::path& path, const std::string& header);

// Puts the file in place; throws std::runtime_error naming `path` and the OS's reason on a write
// failure (disk full), so a truncated export is never reported as success and never replaces
// an older file.
void finish(AtomicOstream& out, const std::filesystem::path& path);

}  // namespace tactile::csv
