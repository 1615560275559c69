#include "playback.hpp"

#include <fmt/format.h>

#include "tactile/display/devices.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/preview.hpp"
#include "tactile/display/summary.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile/display/viewer.hpp"

namespace tactile::cli {

namespace {

void print_report(const display::PlaybackReport& r) {
  fmt::print(
      "play: {} frames played at {:g} Hz ({:.2f} s device time, {:.3f} s wall), {} underruns, "
      "{} malformed, {} samples clamped, {} slew-limited\n",
      r.frames_played, r.rate_hz, r.duration_s, r.wall_s, r.underruns, r.malformed,
      r.clamped_samples, r.slew_limited_samples);
}

int play_headless(const display::TactileMovie& movie, const PlayChoice& choice) {
  display::EmulatedDeviceOptions device;
  device.layout = movie.layout;
  display::PlayOptions options;
  options.loops = choice.loops;
  display::PlaybackReport report;
  const display::TactileMovie output =
      display::render_through_device(movie, device, options, &report);
  print_report(report);
  display::write_preview_strip(choice.preview_png, output, display::PreviewOptions{});
  fmt::print("{}", display::format_summary(display::summarize(output)));
  fmt::print("play: preview of what the emulated device output -> {}\n",
             choice.preview_png.string());
  return 0;
}

// The vendor interface (libusb) when the display offers it, else its HID interface: bulk
// carries every array size at full rate, HID at full speed only small ones (docs/protocol.md).
const display::DeviceDescription* pick_device(const std::vector<display::DeviceDescription>& all) {
  for (const char* backend : {"libusb", "hidapi"}) {
    for (const auto& d : all) {
      if (d.backend == backend && d.accessible) return &d;
    }
  }
  return nullptr;
}

int play_on_device(const display::TactileMovie& movie, const PlayChoice& choice,
                   const display::DeviceDescription& device) {
  fmt::print("play: streaming to {} {} ({} {})\n",
             device.product.empty() ? "display" : device.product, device.serial, device.backend,
             device.path);
  auto transport = display::open_usb_transport(device);
  display::PlayOptions options;
  options.loops = choice.loops;
  // TransportError (unplugged, refused) propagates: the command fails with its message.
  const display::PlaybackReport report = display::play_movie(movie, *transport, options);
  print_report(report);
  return 0;
}

}  // namespace

int play_anywhere(const display::TactileMovie& movie, const PlayChoice& choice) {
  if (!choice.headless) {
    const auto devices = display::list_usb_devices();
    if (const auto* device = pick_device(devices)) return play_on_device(movie, choice, *device);
    if (!devices.empty()) {
      fmt::print(
          "play: found a display at {} but cannot open it (permissions: install "
          "display/udev/70-tactile-display.rules, see README); using the emulator\n",
          devices.front().path);
    }
    if (display::screen_available()) {
      fmt::print("play: no display attached; opening the emulator window\n");
      display::ViewerOptions viewer;
      viewer.loop = choice.loops > 1;
      display::run_viewer(movie, viewer);
      return 0;
    }
    fmt::print(
        "play: no display attached and no screen; playing headless into the emulated "
        "device\n");
  } else {
    fmt::print("play: headless (emulated device)\n");
  }
  return play_headless(movie, choice);
}

}  // namespace tactile::cli
