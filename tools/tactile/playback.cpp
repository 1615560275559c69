#include "playback.hpp"

#include <fmt/format.h>

#include "tactile/display/devices.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/preview.hpp"
#include "tactile/display/summary.hpp"
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

}  // namespace

int play_anywhere(const display::TactileMovie& movie, const PlayChoice& choice) {
  if (!choice.headless) {
    const auto devices = display::list_usb_devices();
    if (!devices.empty()) {
      // Streaming to hardware needs the libusb/hidapi transports (issue 4); until they exist we
      // say so plainly and fall through to the emulator rather than pretend.
      fmt::print(
          "play: found {} ({}) but hardware streaming is not implemented yet; using the "
          "emulator\n",
          devices.front().product.empty() ? "a display" : devices.front().product,
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
