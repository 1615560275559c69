// Where a movie plays; see playback_plan.hpp.

#include "tactile/display/playback_plan.hpp"

#include <fmt/format.h>

#include "tactile/display/summary.hpp"

namespace tactile::display {

std::optional<DeviceDescription> pick_device(const std::vector<DeviceDescription>& devices) {
  // Bulk carries every array size at full rate, HID at full speed only small ones
  // (docs/protocol.md).
  for (const Backend backend : {Backend::libusb, Backend::hidapi}) {
    for (const auto& d : devices) {
      if (d.backend == backend && d.accessible) return d;
    }
  }
  return std::nullopt;
}

PlaybackPlan plan_playback(bool headless, const std::vector<DeviceDescription>& devices,
                           const std::function<bool()>& screen) {
  PlaybackPlan plan;
  if (headless) return plan;
  plan.device = pick_device(devices);
  if (plan.device) {
    plan.target = PlaybackTarget::device;
    return plan;
  }
  if (!devices.empty()) plan.unopenable = devices.front();
  plan.target = screen() ? PlaybackTarget::window : PlaybackTarget::headless;
  return plan;
}

std::string streaming_to(const DeviceDescription& device) {
  return fmt::format("streaming to {} {} ({} {})\n",
                     device.product.empty() ? "display" : device.product, device.serial,
                     to_string(device.backend), device.path);
}

std::string cannot_open(const DeviceDescription& device) {
  return fmt::format(
      "found a display at {} but cannot open it (permissions: install "
      "display/udev/70-tactile-display.rules, see README); using the emulator\n",
      device.path);
}

std::string playback_summary_line(const PlaybackReport& r) {
  // The movie's own length apart from the ramps, so that it reads as `info` and `map` count it.
  return fmt::format(
      "{} frames played at {:g} Hz (of {}; {:.2f} s device time, {:.3f} s wall), {} underruns, "
      "{} malformed, {} samples clamped, {} slew-limited{}\n",
      r.frames_played, r.rate_hz, frame_count_text(r.movie_frames, r.ramp_frames), r.duration_s,
      r.wall_s, r.underruns, r.malformed, r.clamped_samples, r.slew_limited_samples,
      r.interrupted ? "; stopped by a stop request, every contactor ramped to rest" : "");
}

}  // namespace tactile::display
