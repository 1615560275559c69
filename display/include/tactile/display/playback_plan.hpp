#pragma once
// Where `tactile play` sends a movie, decided from what is attached and whether a screen exists,
// before anything is opened: a display if one can be opened, else the emulator window if there
// is a screen, else headless into the emulated device.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tactile/display/devices.hpp"
#include "tactile/display/player.hpp"

namespace tactile::display {

// `latero` is never planned: it is asked for (ResolvedPlay::latero in play_anywhere.hpp).
enum class PlaybackTarget { device, window, headless, latero };

struct PlaybackPlan {
  PlaybackTarget target = PlaybackTarget::headless;
  std::optional<DeviceDescription> device;  // target device: the one to open
  // A display is attached but none can be opened (permissions): worth telling the user, since
  // the movie then goes elsewhere although a display is there.
  std::optional<DeviceDescription> unopenable;
};

// The vendor interface (libusb) of an accessible display when one offers it, else an accessible
// HID interface, else nothing.
std::optional<DeviceDescription> pick_device(const std::vector<DeviceDescription>& devices);

// `headless`: skip device and window even when present. `screen` is asked only when no device
// can take the movie (probing a screen opens a connection to it).
PlaybackPlan plan_playback(bool headless, const std::vector<DeviceDescription>& devices,
                           const std::function<bool()>& screen);

// What a front end says of the plan's display, without its own prefix, ending in a newline:
// "streaming to PRODUCT SERIAL (BACKEND PATH)", and for an attached display it cannot open, why
// and what to install.
std::string streaming_to(const DeviceDescription& device);
std::string cannot_open(const DeviceDescription& device);

// What a playback did in one line ending in a newline, as `tactile play` prints it
// (format_playback_report in player.hpp gives the full account).
std::string playback_summary_line(const PlaybackReport& report);

}  // namespace tactile::display
