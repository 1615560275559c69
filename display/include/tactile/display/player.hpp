#pragma once
// Device-paced streaming of a tactile movie: the device owns the clock and the host keeps its
// FIFO about half full (like asynchronous USB audio), so host hiccups cost no jitter at the
// skin as long as they are shorter than half the FIFO.

#include <chrono>
#include <cstdint>
#include <string>

#include "tactile/display/emulated_device.hpp"
#include "tactile/display/transport.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::display {

struct PlayOptions {
  // Raised-cosine ramps from neutral to the first frame and from the last frame back to
  // neutral, so the skin never feels a step when playback starts or stops.
  double ramp_s = 0.05;
  double target_fill = 0.5;  // fraction of the device FIFO the host keeps queued
  int loops = 1;             // times the movie is played (ramps only at the very start and end)
  // Refuse the movie when a deflection lies outside the device range (default), or send it
  // and let the firmware clamp it.
  bool allow_out_of_range = false;
  // The stream fails with TransportError when the device plays nothing for this long.
  std::chrono::milliseconds stall_timeout{1000};
  // Readable: stop between two frames (tactile::StopSignals::fd(), common/stop_signals.hpp).
  // The device is then stopped, which ramps every contactor from where it is to rest at its
  // own slew limit, and the player waits out that ramp before it returns. -1: never.
  int stop_fd = -1;
};

struct PlaybackReport {
  std::int64_t movie_frames = 0;  // frames of the movie, times loops
  std::int64_t ramp_frames = 0;   // frames added by the start and stop ramps
  std::int64_t frames_sent = 0;
  std::int64_t frames_played = 0;  // as counted by the device
  std::int64_t underruns = 0;
  std::int64_t malformed = 0;
  std::int64_t overflows = 0;  // frames the device refused for lack of room (then resent)
  std::int64_t watchdog_trips = 0;
  std::int64_t clamped_samples = 0;
  std::int64_t slew_limited_samples = 0;
  std::uint32_t max_fifo_fill = 0;
  std::uint32_t min_fifo_fill = 0;  // while streaming, after the FIFO first reached its target
  double rate_hz = 0;
  double duration_s = 0;     // device time from start to the last frame played
  double wall_s = 0;         // host wall-clock time spent in play_movie
  bool interrupted = false;  // stopped by options.stop_fd before the movie's end
};

// Throws std::invalid_argument naming the first reason the movie cannot play on the device:
// grid size or pitch differs, rate above the device maximum or not a whole number of hertz,
// deflections outside the device range (unless allowed), movie invalid.
void check_movie_against_device(const movie::TactileMovie& movie, const DeviceInfo& device,
                                const PlayOptions& options = {});
// The part of it that needs no frames (a live session's, before any is made): grid size and
// pitch of `layout` against the device's, `rate_hz` against its maximum.
void check_layout_against_device(const movie::Layout& layout, double rate_hz,
                                 const DeviceInfo& device);

// Checks, starts the device at the movie's rate, streams ramp-in, the movie (loops times) and
// ramp-out (last frame marked end-of-stream), waits for the FIFO to drain, stops the device
// and reports the device's counters. Asked to stop (options.stop_fd), it stops the device,
// waits for its ramp to rest and reports the counters so far, marked interrupted. Throws
// TransportError when the link fails or stalls.
PlaybackReport play_movie(const movie::TactileMovie& movie, Transport& transport,
                          const PlayOptions& options = {});

// Several lines of text for people: frames sent/played, underruns, malformed, clamped, times.
std::string format_playback_report(const PlaybackReport& report);

// Plays the movie into a simulated-clock emulated device and returns what the firmware output
// (ramps included): what the viewer shows. `device.clock` is forced to simulated. `states`,
// when given, receives the firmware's state after each output frame.
movie::TactileMovie render_through_device(const movie::TactileMovie& movie,
                                          EmulatedDeviceOptions device,
                                          const PlayOptions& options = {},
                                          PlaybackReport* report = nullptr,
                                          std::vector<DeviceTick>* states = nullptr);

}  // namespace tactile::display
