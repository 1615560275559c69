#pragma once
// Tactile movie files: HDF5 (the format users keep, schema in docs/formats.md) and CSV export.

#include <filesystem>

#include "tactile/movie/tactile_movie.hpp"

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

// Reads a movie written by write_tactile_movie. Throws tactile::FormatError naming the file and
// the problem: missing, empty, truncated or not HDF5; wrong format attribute or version;
// missing attribute or dataset; wrong dataset type or rank; sizes that disagree with the
// layout; non-finite deflections.
TactileMovie read_tactile_movie(const std::filesystem::path& path);

// Exports one row per frame: `frame,t_s,r0c0_um,r0c1_um,...` (row-major contactor order,
// t_s = frame / rate_hz). Throws std::runtime_error if the file cannot be written.
void export_tactile_csv(const std::filesystem::path& csv_path, const TactileMovie& movie);

}  // namespace tactile::movie
