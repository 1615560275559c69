#pragma once
// The player through a USB transport, checked the same way for every back end: a 0.2 s STReSS
// movie at 700 Hz reaches the device whole (ramps included), none of it malformed.

#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

#include <filesystem>

#include "../common/temp_dir.hpp"
#include "../movie/test_movies.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/display/player.hpp"
#include "tactile/live/live_request.hpp"
#include "tactile/live/live_session.hpp"

namespace tactile::display::testing {

inline PlaybackReport play_and_check(Transport& transport) {
  const movie::TactileMovie movie =
      movie::testing::sine_movie(movie::stress_layout(), 700, 140, 20);
  const PlaybackReport r = play_movie(movie, transport);
  std::printf("%s", format_playback_report(r).c_str());
  EXPECT_EQ(r.frames_played, r.frames_sent);
  EXPECT_EQ(r.frames_sent, r.movie_frames + r.ramp_frames);
  EXPECT_EQ(r.malformed, 0);
  return r;
}

// Plays a 2 s movie of contactors held at +20 um and raises `sig` in this thread once 300
// frames have gone (0.43 s in), while `stop` (created by the caller before the device was
// opened) watches for it: the player must stop there, well before the end.
inline PlaybackReport play_and_signal(Transport& transport, StopSignals& stop, int sig) {
  class Raising final : public Transport {
   public:
    Raising(Transport& t, int sig) : t_(t), sig_(sig) {}
    DeviceInfo info() override { return t_.info(); }
    void start(double rate_hz) override { t_.start(rate_hz); }
    void stop() override { t_.stop(); }
    bool send_frame(std::span<const std::uint8_t> f) override {
      const bool taken = t_.send_frame(f);
      if (taken && ++sent_ == 300) ::raise(sig_);
      return taken;
    }
    DeviceStatus status() override { return t_.status(); }
    void wait(std::chrono::nanoseconds d) override { t_.wait(d); }

   private:
    Transport& t_;
    int sig_;
    int sent_ = 0;
  };
  movie::TactileMovie movie = movie::testing::sine_movie(movie::stress_layout(), 700, 1400, 0);
  std::fill(movie.deflection_um.begin(), movie.deflection_um.end(), 20.0f);
  Raising raising(transport, sig);
  PlayOptions options;
  options.stop_fd = stop.fd();
  const PlaybackReport r = play_movie(movie, raising, options);
  std::printf("%s", format_playback_report(r).c_str());
  EXPECT_TRUE(r.interrupted);
  EXPECT_EQ(stop.received(), sig);
  EXPECT_GE(r.frames_sent, 300);
  EXPECT_LT(r.frames_sent, 400);
  return r;
}

// A live session on `transport`: 12 frames of a real print rehearsed as a 20 Hz camera, each
// measured, mapped onto the STReSS layout and streamed at the device's rate. Every device frame
// the session sent reached the firmware, none malformed; the session returns the summary.
inline live::LiveSummary live_and_check(Transport& transport) {
  const tactile::test::TempDir dir("live-usb");
  const std::filesystem::path print =
      std::filesystem::path(TACTILE_TEST_DATA_DIR) / "polyu-hrf-pores" / "image_12.jpg";
  for (int f = 0; f < 12; ++f) {
    std::filesystem::copy_file(print, dir.path() / fmt::format("frame_{:03d}.jpg", f));
  }
  live::LiveRequest request;
  request.source = dir.path().string();
  request.capture.px_per_mm = 47;
  request.capture.rate_hz = 20;
  const live::ResolvedLive session = live::resolve(request, OptionSpelling::cli);
  std::atomic<bool> stop{false};
  const live::LiveSummary summary = live::run_live(session, transport, stop);
  std::printf("%s", live::format_summary(summary).c_str());
  EXPECT_EQ(summary.frames_in, 12);
  EXPECT_GT(summary.frames_processed, 0);
  EXPECT_GT(summary.device_frames_sent, 100);  // 0.6 s of a 700 Hz device
  const DeviceStatus status = transport.status();
  EXPECT_EQ(static_cast<std::int64_t>(status.frames_received), summary.device_frames_sent);
  EXPECT_EQ(status.malformed, 0u);
  return summary;
}

}  // namespace tactile::display::testing
