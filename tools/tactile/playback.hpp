#pragma once
// Where a movie plays: a display if one is attached, else the emulator window if there is a
// screen, else headless into the emulated device with a preview image and a printed summary.

#include <filesystem>
#include <optional>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::cli {

struct PlayChoice {
  bool headless = false;                              // skip device and window even when present
  std::filesystem::path preview_png = "preview.png";  // written when playing headless
  int loops = 1;
  int stop_fd = -1;  // readable: stop playing, ramp to rest (display::PlayOptions::stop_fd)
};

// Returns 0; a stopped playback returns 0 too, after its summary (the caller knows the signal).
int play_anywhere(const movie::TactileMovie& movie, const PlayChoice& choice);

}  // namespace tactile::cli
