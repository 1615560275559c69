#include "playback.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tactile/common/stop_signals.hpp"
#include "tactile/display/devices.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/playback_plan.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/preview.hpp"
#include "tactile/display/summary.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile/display/viewer.hpp"

namespace tactile::cli {

namespace {

void print_report(const display::PlaybackReport& r) {
  fmt::print("play: {}", display::playback_summary_line(r));
}

int play_headless(const movie::TactileMovie& movie, const PlayChoice& choice) {
  display::EmulatedDeviceOptions device;
  device.layout = movie.layout;
  display::PlayOptions options;
  options.loops = choice.loops;
  options.stop_fd = choice.stop_fd;
  display::PlaybackReport report;
  const movie::TactileMovie output =
      display::render_through_device(movie, device, options, &report);
  print_report(report);
  // Where the firmware left its outputs, measured on them: at rest (0) after any stop.
  float farthest_um = 0;
  if (output.frame_count > 0) {
    for (const float v : output.frame(output.frame_count - 1)) {
      farthest_um = std::max(farthest_um, std::abs(v));
    }
  }
  fmt::print("play: the emulated device's outputs ended at most {:g} um from rest\n", farthest_um);
  if (report.interrupted || stop_requested(choice.stop_fd)) {
    // A stopped run writes nothing: a preview of part of the movie would pass for all of it.
    fmt::print("play: stopped; no preview written\n");
    return 0;
  }
  display::write_preview_strip(choice.preview_png, output, display::PreviewOptions{});
  fmt::print("{}", display::format_summary(display::summarize(output)));
  fmt::print("play: preview of what the emulated device output -> {}\n",
             choice.preview_png.string());
  return 0;
}

int play_on_device(const movie::TactileMovie& movie, const PlayChoice& choice,
                   const display::DeviceDescription& device) {
  fmt::print("play: streaming to {} {} ({} {})\n",
             device.product.empty() ? "display" : device.product, device.serial,
             to_string(device.backend), device.path);
  auto transport = display::open_usb_transport(device);
  display::PlayOptions options;
  options.loops = choice.loops;
  options.stop_fd = choice.stop_fd;
  // TransportError (unplugged, refused) propagates: the command fails with its message.
  print_report(display::play_movie(movie, *transport, options));
  return 0;
}

}  // namespace

int play_anywhere(const movie::TactileMovie& movie, const PlayChoice& choice) {
  const auto devices =
      choice.headless ? std::vector<display::DeviceDescription>{} : display::list_usb_devices();
  const display::PlaybackPlan plan =
      display::plan_playback(choice.headless, devices, display::screen_available);
  if (plan.unopenable) {
    fmt::print(
        "play: found a display at {} but cannot open it (permissions: install "
        "display/udev/70-tactile-display.rules, see README); using the emulator\n",
        plan.unopenable->path);
  }
  switch (plan.target) {
    case display::PlaybackTarget::device:
      return play_on_device(movie, choice, *plan.device);
    case display::PlaybackTarget::window: {
      fmt::print("play: no display attached; opening the emulator window\n");
      display::ViewerOptions viewer;
      viewer.loop = choice.loops > 1;
      viewer.play.stop_fd = choice.stop_fd;
      const display::ViewerResult r = display::run_viewer(movie, viewer);
      if (stop_requested(choice.stop_fd)) {
        fmt::print("play: window closed by a stop request at frame {} of {} ({} drawn)\n",
                   r.last_movie_frame + 1, r.shown_frame_count, r.frames_drawn);
      }
      return 0;
    }
    case display::PlaybackTarget::headless:
      break;
  }
  fmt::print("play: {}\n", choice.headless ? "headless (emulated device)"
                                           : "no display attached and no screen; playing "
                                             "headless into the emulated device");
  return play_headless(movie, choice);
}

}  // namespace tactile::cli
