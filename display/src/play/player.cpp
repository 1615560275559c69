// Device-paced streaming; see player.hpp.
#include "tactile/display/player.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "tactile/common/json.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/movie/limits.hpp"

namespace tactile::display {

namespace {

// Produces the frames of a playback one at a time: ramp-in, movie x loops, ramp-out.
class FrameSource {
 public:
  FrameSource(const movie::TactileMovie& movie, const PlayOptions& o)
      : movie_(movie),
        loops_(std::max(1, o.loops)),
        ramp_(movie.frame_count > 0
                  ? static_cast<std::int64_t>(std::lround(o.ramp_s * movie.rate_hz))
                  : 0),
        frame_(static_cast<std::size_t>(movie.layout.contactor_count())) {}

  std::int64_t ramp_frames() const { return 2 * ramp_; }
  std::int64_t movie_frames() const { return std::int64_t{movie_.frame_count} * loops_; }
  std::int64_t total() const { return ramp_frames() + movie_frames(); }

  // Frame `k` of the playback.
  std::span<const float> at(std::int64_t k) {
    if (k < ramp_) {
      // Raised cosine that stops one step short of 1: the next frame is the movie's first.
      const double w =
          0.5 - 0.5 * std::cos(std::numbers::pi * static_cast<double>(k + 1) / (ramp_ + 1));
      return scaled(movie_.frame(0), w);
    }
    k -= ramp_;
    if (k < movie_frames()) return movie_.frame(static_cast<std::int32_t>(k % movie_.frame_count));
    k -= movie_frames();
    // Ends exactly at neutral.
    const double w = 0.5 + 0.5 * std::cos(std::numbers::pi * static_cast<double>(k + 1) / ramp_);
    return scaled(movie_.frame(movie_.frame_count - 1), w);
  }

 private:
  std::span<const float> scaled(std::span<const float> f, double w) {
    for (std::size_t i = 0; i < f.size(); ++i) frame_[i] = static_cast<float>(f[i] * w);
    return frame_;
  }

  const movie::TactileMovie& movie_;
  int loops_;
  std::int64_t ramp_;
  std::vector<float> frame_;
};

// How long the device needs to bring every contactor from anywhere in its range to rest at
// its slew limit, plus two periods for the tick in flight. Zero for a device that ramps
// before stop() returns (no slew limit reported, like the Latero).
std::chrono::nanoseconds ramp_to_rest(const DeviceInfo& info, double rate_hz) {
  if (info.max_slew_um_per_s <= 0) return {};
  const double reach_um =
      std::max(std::abs(info.layout.deflection_min_um), std::abs(info.layout.deflection_max_um));
  return std::chrono::nanoseconds(
      static_cast<std::int64_t>(1e9 * (reach_um / info.max_slew_um_per_s + 2.0 / rate_hz)));
}

bool close(double a, double b) {
  return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b));
}

}  // namespace

void check_layout_against_device(const movie::Layout& m, double rate_hz, const DeviceInfo& device) {
  const movie::Layout& d = device.layout;
  if (m.rows != d.rows || m.cols != d.cols) {
    throw std::invalid_argument(
        fmt::format("movie layout '{}' is {} x {} contactors but device '{}' ({}) has {} x {}",
                    m.name, m.rows, m.cols, device.name, d.name, d.rows, d.cols));
  }
  if (!close(m.pitch_x_mm, d.pitch_x_mm) || !close(m.pitch_y_mm, d.pitch_y_mm)) {
    throw std::invalid_argument(fmt::format(
        "movie layout '{}' has pitch {} x {} mm but device '{}' ({}) has {} x {} mm", m.name,
        m.pitch_x_mm, m.pitch_y_mm, device.name, d.name, d.pitch_x_mm, d.pitch_y_mm));
  }
  if (rate_hz > d.max_rate_hz) {
    throw std::invalid_argument(
        fmt::format("movie rate {} Hz exceeds the device maximum {} Hz", rate_hz, d.max_rate_hz));
  }
  movie::require_playable_rate(rate_hz, "movie rate");
}

void check_movie_against_device(const movie::TactileMovie& movie, const DeviceInfo& device,
                                const PlayOptions& options) {
  validate_movie(movie);
  const movie::Layout& m = movie.layout;
  const movie::Layout& d = device.layout;
  check_layout_against_device(m, movie.rate_hz, device);
  if (!options.allow_out_of_range) {
    const auto n = static_cast<std::size_t>(m.contactor_count());
    for (std::size_t i = 0; i < movie.deflection_um.size(); ++i) {
      const float v = movie.deflection_um[i];
      if (v < d.deflection_min_um - 1e-3 || v > d.deflection_max_um + 1e-3) {
        throw std::invalid_argument(fmt::format(
            "movie deflection {} um at frame {}, contactor {} is outside the device range "
            "[{}, {}] um (allow out-of-range values to let the device clamp them)",
            v, i / n, i % n, d.deflection_min_um, d.deflection_max_um));
      }
    }
  }
}

PlaybackReport play_movie(const movie::TactileMovie& movie, Transport& transport,
                          const PlayOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  const DeviceInfo info = transport.info();
  check_movie_against_device(movie, info, options);
  PlaybackReport report;
  report.rate_hz = movie.rate_hz;
  FrameSource source(movie, options);
  report.movie_frames = source.movie_frames();
  report.ramp_frames = source.ramp_frames();
  const std::int64_t total = source.total();

  const std::uint32_t capacity = std::max<std::uint32_t>(1, info.fifo_capacity_frames);
  const auto target = static_cast<std::uint32_t>(
      std::clamp(std::lround(options.target_fill * capacity), 1L, static_cast<long>(capacity)));
  // Poll twice per device period: often enough to refill before the FIFO falls far below
  // the target, rarely enough to leave the host CPU idle between frames.
  const auto poll = std::chrono::nanoseconds(static_cast<std::int64_t>(0.5e9 / movie.rate_hz));

  transport.start(movie.rate_hz);
  std::int64_t next = 0;
  std::uint64_t last_played = 0;
  std::chrono::nanoseconds since_progress{0};
  bool reached_target = false;
  report.min_fifo_fill = capacity;
  std::vector<std::uint8_t> pending;  // encoded frame `next`, kept until the device takes it
  try {
    for (;;) {
      if (stop_requested(options.stop_fd)) {
        report.interrupted = true;
        break;
      }
      DeviceStatus st = transport.status();
      if (st.frames_played != last_played) {
        since_progress = {};
        last_played = st.frames_played;
      }
      // Measured only while frames remain to be sent; the final drain empties it on purpose.
      if (reached_target && st.streaming && next < total) {
        report.min_fifo_fill = std::min(report.min_fifo_fill, st.fifo_fill);
      }
      std::uint32_t fill = st.fifo_fill;
      while (next < total && fill < target) {
        if (pending.empty()) {
          pending =
              encode_frame(source.at(next), static_cast<std::uint32_t>(next), next + 1 == total);
        }
        if (!transport.send_frame(pending)) break;  // no room after all: wait and resend
        pending.clear();
        ++next;
        ++fill;
      }
      if (fill >= target) reached_target = true;
      report.max_fifo_fill = std::max(report.max_fifo_fill, fill);
      if (next == total && fill == 0) break;  // everything sent and played
      transport.wait(poll);
      since_progress += poll;
      if (since_progress > options.stall_timeout && st.fifo_fill > 0) {
        throw TransportError(fmt::format(
            "device '{}' played no frame for {} ms with {} frames queued; stream aborted",
            info.name, options.stall_timeout.count(), st.fifo_fill));
      }
    }
  } catch (...) {
    try {
      transport.stop();
    } catch (...) {
      // The original error says more than a failed stop on a dead link.
    }
    throw;
  }
  if (report.interrupted) {
    // Queued frames are dropped; the device walks every output back to rest.
    transport.stop();
    const auto ramp = ramp_to_rest(info, movie.rate_hz);
    for (std::chrono::nanoseconds waited{0}; waited < ramp; waited += poll) transport.wait(poll);
  }
  const DeviceStatus st = transport.status();
  if (!report.interrupted) transport.stop();
  report.frames_sent = next;
  report.frames_played = static_cast<std::int64_t>(st.frames_played);
  report.underruns = static_cast<std::int64_t>(st.underruns);
  report.malformed = static_cast<std::int64_t>(st.malformed);
  report.overflows = static_cast<std::int64_t>(st.overflows);
  report.watchdog_trips = static_cast<std::int64_t>(st.watchdog_trips);
  report.clamped_samples = static_cast<std::int64_t>(st.clamped_samples);
  report.slew_limited_samples = static_cast<std::int64_t>(st.slew_limited_samples);
  if (!reached_target) report.min_fifo_fill = 0;
  report.duration_s = static_cast<double>(st.frames_played) / movie.rate_hz;
  report.wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return report;
}

std::string format_playback_report(const PlaybackReport& r) {
  std::string out;
  if (r.interrupted) {
    out += "stopped     by a stop request before the end; every contactor ramped to rest\n";
  }
  out += fmt::format("frames      {} sent ({} movie + {} ramp), {} played at {} Hz\n",
                     r.frames_sent, r.movie_frames, r.ramp_frames, r.frames_played, r.rate_hz);
  out += fmt::format("timing      {:.3f} s on the device, {:.3f} s wall clock\n", r.duration_s,
                     r.wall_s);
  out += fmt::format("device fifo {}..{} frames while streaming; {} underruns, {} overflows\n",
                     r.min_fifo_fill, r.max_fifo_fill, r.underruns, r.overflows);
  out += fmt::format(
      "safety      {} malformed frames, {} clamped samples, {} slew-limited, "
      "{} watchdog trips\n",
      r.malformed, r.clamped_samples, r.slew_limited_samples, r.watchdog_trips);
  return out;
}

movie::TactileMovie render_through_device(const movie::TactileMovie& movie,
                                          EmulatedDeviceOptions device, const PlayOptions& options,
                                          PlaybackReport* report, std::vector<DeviceTick>* states) {
  device.clock = EmulatedClock::simulated;
  device.record_outputs = true;
  EmulatedDevice emulator(device);
  const PlaybackReport r = play_movie(movie, emulator, options);
  if (report != nullptr) *report = r;
  if (states != nullptr) *states = emulator.recorded_states();
  movie::TactileMovie out = emulator.recording();
  out.layout = movie.layout;
  // The movie played is in memory, its file unknown here: its whole provenance is a parameter.
  out.provenance =
      make_provenance({}, "emulated device output",
                      nlohmann::json{{"played", provenance_json(movie.provenance)}}.dump());
  return out;
}

}  // namespace tactile::display
