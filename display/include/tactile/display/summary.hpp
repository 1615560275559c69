#pragma once
// Numbers that describe a tactile movie at a glance (printed by `tactile play` when headless).

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::display {

struct MovieSummary {
  std::string layout_name;
  std::int32_t rows = 0;
  std::int32_t cols = 0;
  double rate_hz = 0;
  std::int32_t frame_count = 0;  // the movie's own frames
  // Frames the player added to ramp from and to rest (a played output's; 0 for a movie file).
  std::int32_t ramp_frames = 0;
  double duration_s = 0;
  double peak_deflection_um = 0;  // largest |deflection| of any contactor in any frame
  double rms_deflection_um = 0;   // over all contactors and frames
  double peak_frame_rms_um = 0;   // largest per-frame RMS, and when it occurs
  double peak_frame_t_s = 0;
  // Fraction of samples at or beyond the layout's deflection limits (within 0.05 um, half a
  // wire unit): how much the mapping leaned on the clamp.
  double saturated_fraction = 0;
  double activity_window_s = 0.1;
  std::vector<double> activity_rms_um;  // RMS deflection per consecutive 0.1 s window
};

// RMS deflection over the contactors of each frame.
std::vector<double> frame_rms_um(const movie::TactileMovie& movie);

// Throws std::invalid_argument for an invalid movie (see validate_movie()).
MovieSummary summarize(const movie::TactileMovie& movie);

// Several lines of human-readable text, ending in a newline.
std::string format_summary(const MovieSummary& summary);

// A movie's length in frames as every command prints it: "2077 movie frames" or, played, "2077
// movie frames + 70 frames of ramp from and to rest", so that `map`, `info`, `play` and `view`
// give the same count for the same movie.
std::string frame_count_text(std::int64_t movie_frames, std::int64_t ramp_frames);

}  // namespace tactile::display
