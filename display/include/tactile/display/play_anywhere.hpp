#pragma once
// Where a movie plays, and playing it there: a Latero when asked for one; else a display if one
// is attached, else the emulator window if there is a screen, else headless into the emulated
// device with a preview image and a summary. `tactile play` and the Python module's play() are
// this one function. The core library holds the choice, the Latero and headless play; displays
// on USB and the window come as PlayBackends from the libraries that link libusb and hidapi
// (usb_play_backends, usb_transports.hpp) and GLFW (with_window, viewer.hpp), so a program
// links only the back ends it offers.

#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tactile/display/latero_protocol.hpp"
#include "tactile/display/latero_transport.hpp"
#include "tactile/display/playback_plan.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/transport.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::display {

// A Latero over UDP (`tactile play --latero`): where it answers, and how deflections become its
// raw blade values.
struct LateroPlayTarget {
  std::string address;  // HOST[:PORT] (parse_latero_address)
  LateroBladeMapping mapping;
};

struct ResolvedPlay {
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

using Say = std::function<void(const std::string&)>;

// What play_anywhere may play on besides a Latero and the emulated device. Unset members are
// absent back ends: no display is looked for without list_devices, no window is opened
// without play_in_window (as if there were no screen).
struct PlayBackends {
  std::function<std::vector<DeviceDescription>()> list_devices;
  // Opens a listed device; throws TransportError naming it.
  std::function<std::unique_ptr<Transport>(const DeviceDescription&)> open_device;
  // Asked only when no display takes the movie (probing a screen connects to it).
  std::function<bool()> screen;
  // Plays in the window until it is closed; says what a person should know and sets
  // result.stopped when request.stop_fd closed it.
  std::function<void(const movie::TactileMovie&, const ResolvedPlay&, const Say&, PlayResult&)>
      play_in_window;
};

// Plays `movie` on request.latero, else where plan_playback sends it among `backends`, and tells a
// person what happens through `say` (one or more lines, each ending in a newline: what `tactile
// play` prints). Throws TransportError when a display or the Latero fails (or its name does not
// resolve), std::invalid_argument when the movie does not fit the device (a Latero: another
// layout than `latero`, named with the command that maps for it), the Latero's address does not
// parse or its blade mapping is inconsistent (validate_blade_mapping).
PlayResult play_anywhere(const movie::TactileMovie& movie, const ResolvedPlay& request,
                         const Say& say, const PlayBackends& backends);

}  // namespace tactile::display
