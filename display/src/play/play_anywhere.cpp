// Where a movie plays, and playing it there; see play_anywhere.hpp.

#include "tactile/display/play_anywhere.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tactile/common/stop_signals.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/latero_transport.hpp"
#include "tactile/display/preview.hpp"
#include "tactile/display/summary.hpp"

namespace tactile::display {

namespace {

void play_headless(const movie::TactileMovie& movie, const ResolvedPlay& request, const Say& say,
                   PlayResult& result) {
  EmulatedDeviceOptions device;
  device.layout = movie.layout;
  PlayOptions options;
  options.loops = request.loops;
  options.stop_fd = request.stop_fd;
  PlaybackReport report;
  const movie::TactileMovie output = render_through_device(movie, device, options, &report);
  result.report = report;
  say("play: " + playback_summary_line(report));
  // Where the firmware left its outputs, measured on them: at rest (0) after any stop.
  float farthest_um = 0;
  if (output.frame_count > 0) {
    for (const float v : output.frame(output.frame_count - 1)) {
      farthest_um = std::max(farthest_um, std::abs(v));
    }
  }
  result.final_max_um = farthest_um;
  say(fmt::format("play: the emulated device's outputs ended at most {:g} um from rest\n",
                  farthest_um));
  if (report.interrupted || stop_requested(request.stop_fd)) {
    // A stopped run writes nothing: a preview of part of the movie would pass for all of it.
    result.stopped = true;
    say("play: stopped; no preview written\n");
    return;
  }
  MovieSummary summary = summarize(output);
  // The output holds the ramps the player added: counted apart, as the line above counts them.
  summary.ramp_frames = static_cast<std::int32_t>(report.ramp_frames);
  summary.frame_count -= summary.ramp_frames;
  say(format_summary(summary));
  if (request.preview_png.empty()) return;
  write_preview_strip(request.preview_png, output, PreviewOptions{});
  result.preview_png = request.preview_png;
  say(fmt::format("play: preview of what the emulated device output -> {}\n",
                  request.preview_png.string()));
}

void play_on_device(const movie::TactileMovie& movie, const ResolvedPlay& request,
                    const DeviceDescription& device, const PlayBackends& backends, const Say& say,
                    PlayResult& result) {
  say("play: " + streaming_to(device));
  auto transport = backends.open_device(device);
  PlayOptions options;
  options.loops = request.loops;
  options.stop_fd = request.stop_fd;
  // TransportError (unplugged, refused) propagates: the caller fails with its message.
  result.report = play_movie(movie, *transport, options);
  result.stopped = result.report->interrupted;
  say("play: " + playback_summary_line(*result.report));
}

// A movie for another layout cannot play on the Latero's 8 x 8 blades; say what would.
void check_latero_movie(const movie::TactileMovie& movie) {
  const movie::Layout latero = movie::latero_layout();
  const movie::Layout& m = movie.layout;
  if (m.rows != latero.rows || m.cols != latero.cols ||
      std::abs(m.pitch_x_mm - latero.pitch_x_mm) > 1e-6 ||
      std::abs(m.pitch_y_mm - latero.pitch_y_mm) > 1e-6) {
    throw std::invalid_argument(fmt::format(
        "the movie is for layout '{}' ({} x {} at {:g} x {:g} mm) but a Latero has layout "
        "'latero' ({} x {} at {:g} x {:g} mm); map the strain movie again with `tactile map "
        "STRAIN.h5 --layout latero --out MOVIE.h5`",
        m.name, m.rows, m.cols, m.pitch_x_mm, m.pitch_y_mm, latero.rows, latero.cols,
        latero.pitch_x_mm, latero.pitch_y_mm));
  }
}

void play_on_latero(const movie::TactileMovie& movie, const ResolvedPlay& request, const Say& say,
                    PlayResult& result) {
  check_latero_movie(movie);
  const LateroPlayTarget& target = *request.latero;
  LateroTransportOptions transport;
  transport.mapping = target.mapping;
  validate_blade_mapping(transport.mapping);
  LateroTransport latero(parse_latero_address(target.address), transport);
  result.latero_address = latero.address();
  const LateroBladeMapping& b = target.mapping;
  say(fmt::format(
      "play: streaming to the Latero at {} at {:g} Hz (paced by this computer's clock); blades: "
      "raw {:g} at rest, {:+g} per {:g} um, at most {:g}\n",
      latero.address().text(), movie.rate_hz, b.centre_raw, b.raw_per_unit, b.full_scale_um,
      b.max_raw));
  PlayOptions options;
  options.loops = request.loops;
  options.stop_fd = request.stop_fd;
  // A stop request ends the stream between two frames; the transport's stop() then ramps every
  // blade from where it is back to centre.
  result.report = play_movie(movie, latero, options);
  result.stopped = result.report->interrupted;
  result.latero_link = latero.stats();
  say(format_playback_report(*result.report));
  say(format_latero_link(*result.latero_link, movie.rate_hz));
}

}  // namespace

PlayResult play_anywhere(const movie::TactileMovie& movie, const ResolvedPlay& request,
                         const Say& say, const PlayBackends& backends) {
  if (request.latero) {
    PlayResult result;
    result.target = PlaybackTarget::latero;
    play_on_latero(movie, request, say, result);
    return result;
  }
  const bool usb = backends.list_devices && backends.open_device;
  const bool window = backends.screen && backends.play_in_window;
  const auto devices =
      request.headless || !usb ? std::vector<DeviceDescription>{} : backends.list_devices();
  const PlaybackPlan plan =
      plan_playback(request.headless, devices, [&] { return window && backends.screen(); });
  PlayResult result;
  result.target = plan.target;
  result.device = plan.device;
  if (plan.unopenable) {
    say("play: " + cannot_open(*plan.unopenable));
  }
  switch (plan.target) {
    case PlaybackTarget::device:
      play_on_device(movie, request, *plan.device, backends, say, result);
      return result;
    case PlaybackTarget::window:
      say("play: no display attached; opening the emulator window\n");
      backends.play_in_window(movie, request, say, result);
      return result;
    case PlaybackTarget::headless:
    case PlaybackTarget::latero:  // never planned
      break;
  }
  // Without a window back end whether there is a screen was never asked: say so honestly.
  say(fmt::format("play: {}\n", request.headless ? "headless (emulated device)"
                                : window         ? "no display attached and no screen; playing "
                                                   "headless into the emulated device"
                                                 : "no display attached; playing headless into "
                                                   "the emulated device (no emulator window in "
                                                   "this program)"));
  play_headless(movie, request, say, result);
  return result;
}

}  // namespace tactile::display
