#pragma once
// A tactile movie as a multichannel WAV file for audio-driven rigs: one channel per contactor
// (row-major, as in the CSV export) at the movie's rate, 32-bit float samples, each the
// deflection divided by full_scale_um(movie) (hjif.hpp), so that 1.0 is the largest deflection
// the display (or the movie) reaches. Layout in docs/formats.md.

#include <cstdint>
#include <filesystem>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::movie {

// WAV sizes are 32-bit: the data may take at most this many bytes.
inline constexpr std::uint64_t kWavMaxDataBytes = 0xFFFFFFFFULL - 80;

// Writes `movie` as WAVE_FORMAT_EXTENSIBLE with IEEE float samples, atomically. Returns the
// full scale in micrometres (the deflection written as 1.0). Throws std::invalid_argument if the
// movie is inconsistent, its rate is not a whole number of hertz, it has more than 65535
// contactors or its data exceed the 4 GB a WAV file can hold; std::runtime_error if the file
// cannot be written.
double write_wav(const TactileMovie& movie, const std::filesystem::path& path);

}  // namespace tactile::movie
