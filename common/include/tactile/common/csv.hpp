#pragma once
// Minimal CSV writing for exports: numbers and plain identifiers only, so no quoting is needed;
// and the line reader every CSV reader shares.

#include <cstddef>
#include <filesystem>
#include <istream>
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

// The lines of a text file as people's tools write them: a spreadsheet saved on Windows ends
// its lines with CR LF, and many editors put a UTF-8 byte-order mark before the first line.
// Both are taken off, so a reader compares and splits only what a person sees.
class LineReader {
 public:
  explicit LineReader(std::istream& in) : in_(in) {}
  // The next line without its line end (LF or CR LF) and, on the first line, without a UTF-8
  // byte-order mark; false at the end of the input.
  bool next(std::string& line);
  // 1-based number of the line next() gave last (0 before the first).
  std::size_t number() const { return number_; }

 private:
  std::istream& in_;
  std::size_t number_ = 0;
};

}  // namespace tactile::csv
