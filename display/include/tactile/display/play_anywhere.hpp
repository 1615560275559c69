#pragma once
// Where a movie plays, and playing it there: a Latero when asked for one; else a display if one
// is attached, else the emulator window if there is a screen, else headless into the emulated
// device with a preview image and a summary. `tactile play` and the Python module's play() are
// this one function.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "tactile/display/latero_protocol.hpp"
#include "tactile/display/latero_transport.hpp"
#include "tactile/display/playback_plan.hpp"
#include "tactile/display/player.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::display {

// A Latero over UDP (`tactile play --latero`): where it answers, and how deflections become its
// raw blade values.
struct LateroPlayTarget {
  std::string address;  // HOST[:PORT] (parse_latero_address)
  LateroBladeMapping mapping;
};

struct PlayRequest {
  bool headless = false;  // skip device and window even when present
  // Set: play on this Latero and nowhere else (headless is then not looked at).
  std::optional<LateroPlayTarget> latero;
  // Written when playing headless (and not stopped); empty: none.
  std::filesystem::path preview_png;
  int loops = 1;
  int stop_fd = -1;  // readable: stop playing, ramp to rest (PlayOptions::stop_fd)
};

struct PlayResult {
  PlaybackTarget target = PlaybackTarget::headless;
  std::optional<DeviceDescription> device;  // the display played on
  std::optional<PlaybackReport> report;     // the device's or the emulated device's counters
  // A Latero: the address it was reached at and what the sender saw of the link.
  std::optional<LateroAddress> latero_address;
  std::optional<LateroLinkStats> latero_link;
  // Headless: the largest |output| of the emulated device's last frame, um (0 = at rest).
  double final_max_um = 0;
  bool stopped = false;                              // by stop_fd
  std::optional<std::filesystem::path> preview_png;  // written
};

// Plays `movie` on request.latero, else where plan_playback sends it, and tells a person what
// happens through `say` (one or more lines, each ending in a newline: what `tactile play`
// prints). Throws TransportError when a display or the Latero fails (or its name does not
// resolve), std::invalid_argument when the movie does not fit the device (a Latero: another
// layout than `latero`, named with the command that maps for it), the Latero's address does not
// parse or its blade mapping is inconsistent (validate_blade_mapping).
PlayResult play_anywhere(const movie::TactileMovie& movie, const PlayRequest& request,
                         const std::function<void(const std::string&)>& say);

}  // namespace tactile::display
