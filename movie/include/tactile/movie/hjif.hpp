#pragma once
// MPEG-I Haptics interchange files (ISO/IEC 23090-31, `.hjif`, JSON): a tactile movie as one
// `Position` perception with one `Curve` channel per contactor, and back. The mapping, field by
// field, and what is lost, are in docs/formats.md.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::movie {

// Limits of the format (and of its binary form `.hmpg`, into which an HJIF file is re-encoded):
inline constexpr std::int64_t kHjifMaxTimescale = 48000;     // profile Main
inline constexpr std::int32_t kHjifLevel1MaxChannels = 127;  // more needs level 2
inline constexpr std::int32_t kHjifLevel2MaxChannels = 65535;
inline constexpr std::int32_t kHjifMaxGridSide = 127;       // vectors are signed 8-bit
inline constexpr std::int64_t kHjifMaxEffectTicks = 65535;  // keyframe positions: 16 bits
inline constexpr std::int64_t kHjifMaxEffectPosition = (1 << 25) - 1;  // 25 bits
inline constexpr std::int64_t kHjifMaxKeyframes = 65535;      // keyframes per effect: 16 bits
inline constexpr std::size_t kHjifMaxDescriptionBytes = 255;  // descriptions: 8-bit length
// Amplitudes are written as multiples of this fraction of the full scale.
inline constexpr double kHjifAmplitudeStep = 1e-6;

struct HjifOptions {
  // timescale = rate_hz * ticks_per_sample, so that every sample falls on a whole tick.
  std::int32_t ticks_per_sample = 1;
  // An effect spans at most this many ticks; a longer movie is split into several effects.
  std::int64_t max_effect_ticks = kHjifMaxEffectTicks;
};

// What write_hjif wrote, for the command's summary and for tests.
struct HjifSummary {
  std::int32_t channels = 0;
  std::int32_t level = 1;
  std::int64_t timescale = 0;
  std::int32_t effects_per_channel = 0;
  double full_scale_um = 0;  // deflection written as amplitude 1
};

// The full scale of a movie's amplitudes: the larger of the layout's deflection range and the
// largest deflection in the movie (a movie may exceed its layout's range), micrometres.
double full_scale_um(const TactileMovie& movie);

// The movie as HJIF text. Throws std::invalid_argument naming the limit a movie exceeds (a rate
// that is not a whole number of hertz or exceeds the timescale limit, a grid side over 127, more
// than 65535 contactors, no frames, a layout name that makes a description over 255 bytes).
std::string hjif_text(const TactileMovie& movie, const HjifOptions& options = {},
                      HjifSummary* summary = nullptr);

// hjif_text written atomically to `path`.
HjifSummary write_hjif(const TactileMovie& movie, const std::filesystem::path& path,
                       const HjifOptions& options = {});

struct HjifImportOptions {
  // The layout of the display; required when the file does not carry one (a file from another
  // tool), and checked against the file's channel grid and direction.
  std::optional<Layout> layout;
};

// Parses HJIF text. `where` names the source in messages. Throws tactile::FormatError naming
// the field and the problem: not JSON, a missing or mistyped field, a profile, level,
// modality, band or curve type this movie cannot represent, actuator targets outside the
// resolution or not one per contactor, counts beyond the format's or this machine's limits.
TactileMovie parse_hjif(const std::string& text, const std::string& where,
                        const HjifImportOptions& options = {});

// Reads and parses an HJIF file; a missing or unreadable file is a FormatError too.
TactileMovie read_hjif(const std::filesystem::path& path, const HjifImportOptions& options = {});

}  // namespace tactile::movie
