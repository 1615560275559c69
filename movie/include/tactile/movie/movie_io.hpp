#pragma once
// Tactile movie files: HDF5 (the format users keep, schema in docs/formats.md) and CSV export.

#include <cstdint>
#include <filesystem>
#include <vector>

#include "tactile/common/h5_growing.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::h5 {
class ReadingProcess;
}  // namespace tactile::h5

namespace tactile::movie {

// Version of the HDF5 schema written by write_tactile_movie (root attribute format_version).
inline constexpr int kTactileMovieFormatVersion = 1;

// The highest frame rate a movie (or a layout) may declare: far above any display, far
// below rates whose frame time rounds to nothing.
inline constexpr double kMaxMovieRateHz = 100000;
// Pitches and contactor sizes a layout (in a movie or a layout file) may declare, mm.
inline constexpr double kMinLayoutSizeMm = 0.001;
inline constexpr double kMaxLayoutSizeMm = 1000;

// Writes `movie` as HDF5, atomically (an existing file is replaced only on success).
// Throws std::invalid_argument if the movie is inconsistent (see validate_movie()), and
// std::runtime_error if the file cannot be written.
void write_tactile_movie(const std::filesystem::path& path, const TactileMovie& movie);

// A movie written frame by frame into a file that read_tactile_movie opens at every moment, a
// kill or a power cut included, holding every frame up to the last flush(). Rate, layout and
// provenance are `header`'s (its frames are ignored). Creates `path` new (never over a file or
// through a link). Throws as write_tactile_movie does.
class TactileMovieAppender {
 public:
  TactileMovieAppender(const std::filesystem::path& path, const TactileMovie& header);
  // One frame (rows x cols deflections, row-major), kept for the next flush.
  void append(const std::vector<float>& deflection_um);
  // Writes the frames appended since the last flush and syncs them to the disk.
  void flush();
  // Flushes and closes: the file is then as any other movie.
  void close();

 private:
  h5::GrowingFile file_;
  std::size_t frame_size_;
  std::vector<float> pending_;
  std::int64_t frames_ = 0;
};

// Reads a movie written by write_tactile_movie. Throws tactile::FormatError naming the file and
// the problem: missing, empty, truncated or not HDF5; wrong format attribute or version;
// missing attribute or dataset; wrong dataset type or rank; sizes that disagree with the
// layout; non-finite deflections.
// The file is read first in a child process (h5::read_in_child_first): `process`, when given,
// is one kept for many files (h5::ReadingProcess); else one is forked for this file.
TactileMovie read_tactile_movie(const std::filesystem::path& path,
                                h5::ReadingProcess* process = nullptr);

// Exports one row per frame: `frame,t_s,r0c0_um,r0c1_um,...` (row-major contactor order,
// t_s = frame / rate_hz). Throws std::runtime_error if the file cannot be written.
void export_tactile_csv(const std::filesystem::path& csv_path, const TactileMovie& movie);

}  // namespace tactile::movie
