// Streaming through the emulated device: pacing, ordering, limits, checks against the device.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include "../movie/test_movies.hpp"
#include "tactile/display/control_codec.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/display/player.hpp"

namespace tactile::display {
namespace {

using ::testing::HasSubstr;

EmulatedDeviceOptions device_for(const movie::Layout& layout) {
  EmulatedDeviceOptions o;
  o.layout = layout;
  return o;
}

// Plays `movie` in simulated time and checks that the device output is the movie, frame by
// frame, in order: output tick ramp_in + f must equal frame f (quantised to 0.1 um).
void expect_played_exactly(const movie::TactileMovie& movie) {
  EmulatedDevice device(device_for(movie.layout));
  PlayOptions options;
  const PlaybackReport r = play_movie(movie, device, options);
  const std::int64_t ramp_in = r.ramp_frames / 2;
  EXPECT_EQ(r.movie_frames, movie.frame_count);
  EXPECT_EQ(ramp_in, std::lround(options.ramp_s * movie.rate_hz));
  EXPECT_EQ(r.frames_sent, r.movie_frames + r.ramp_frames);
  EXPECT_EQ(r.frames_played, r.frames_sent);
  EXPECT_EQ(r.underruns, 0);
  EXPECT_EQ(r.malformed, 0);
  EXPECT_EQ(r.clamped_samples, 0);
  EXPECT_EQ(r.slew_limited_samples, 0);
  // Device-paced: the FIFO stayed near half full once filled.
  const auto capacity = device.info().fifo_capacity_frames;
  EXPECT_GE(r.min_fifo_fill, capacity / 2 - 2);
  EXPECT_LE(r.max_fifo_fill, capacity / 2 + 1);
  EXPECT_NEAR(r.duration_s, static_cast<double>(r.frames_sent) / movie.rate_hz, 1e-9);
  const movie::TactileMovie out = device.recording();
  ASSERT_EQ(out.frame_count, r.frames_sent);
  for (std::int32_t f = 0; f < movie.frame_count; ++f) {
    const auto want = movie.frame(f);
    const auto got = out.frame(static_cast<std::int32_t>(ramp_in + f));
    for (std::size_t i = 0; i < want.size(); ++i) {
      ASSERT_NEAR(got[i], want[i], 0.05 + 1e-4) << "frame " << f << " contactor " << i;
    }
  }
  // The ramps start and end at neutral.
  const auto first = out.frame(0);
  const auto last = out.frame(out.frame_count - 1);
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_LE(std::abs(first[i]), std::abs(movie.frame(0)[i]) * 0.01 + 0.1);
    EXPECT_EQ(last[i], 0.0f);
  }
}

TEST(Player, StressAt700HzPlaysEveryFrameInOrder) {
  expect_played_exactly(movie::testing::sine_movie(movie::stress_layout(), 700, 2100, 45));  // 3 s
}

TEST(Player, LateroAt750HzPlaysEveryFrameInOrder) {
  expect_played_exactly(movie::testing::sine_movie(movie::latero_layout(), 750, 2250, 90));  // 3 s
}

TEST(Player, SixtySecondsAt1kHzWithoutUnderrunInSimulatedTime) {
  movie::Layout layout = movie::stress_layout();  // 100 contactors, the STReSS grid
  layout.max_rate_hz = 1000;
  EmulatedDeviceOptions o = device_for(layout);
  o.record_outputs = false;
  EmulatedDevice device(o);
  const PlaybackReport r = play_movie(movie::testing::sine_movie(layout, 1000, 60000, 40), device);
  EXPECT_EQ(r.frames_played, r.frames_sent);
  EXPECT_EQ(r.frames_sent, 60000 + r.ramp_frames);
  EXPECT_EQ(r.underruns, 0);
  EXPECT_EQ(r.overflows, 0);
  EXPECT_LT(r.wall_s, 5.0);  // simulated time runs far faster than real time
  const std::string text = format_playback_report(r);
  EXPECT_THAT(text, HasSubstr(fmt::format("{} sent (60000 movie + {} ramp)", r.frames_sent,
                                          r.ramp_frames)));
  EXPECT_THAT(text, HasSubstr("0 underruns"));
}

TEST(Player, OutOfRangeValuesAreClampedByTheFirmwareWhenAllowed) {
  const movie::TactileMovie movie =
      movie::testing::sine_movie(movie::stress_layout(), 700, 700, 80);  // +-80 > +-50
  EmulatedDevice device(device_for(movie.layout));
  PlayOptions options;
  options.allow_out_of_range = true;
  const PlaybackReport r = play_movie(movie, device, options);
  EXPECT_GT(r.clamped_samples, 0);
  EXPECT_EQ(r.frames_played, r.frames_sent);
  const movie::TactileMovie out = device.recording();
  const auto ramp_in = r.ramp_frames / 2;
  int clamped = 0, exact = 0;
  for (std::int32_t f = 0; f < movie.frame_count; ++f) {
    const auto want = movie.frame(f);
    const auto got = out.frame(static_cast<std::int32_t>(ramp_in + f));
    for (std::size_t i = 0; i < want.size(); ++i) {
      const float expected = std::clamp(want[i], -50.0f, 50.0f);
      ASSERT_NEAR(got[i], expected, 0.05 + 1e-4) << "frame " << f << " contactor " << i;
      (std::abs(want[i]) > 50 ? clamped : exact)++;
    }
  }
  EXPECT_GT(clamped, 1000);  // both cases really occurred
  EXPECT_GT(exact, 1000);
}

TEST(Player, SlewLimitShapesAStep) {
  // A 0 -> 40 um step: the firmware limits it to 20 mm/s = 20 um per tick at 1 kHz.
  movie::Layout layout = movie::latero_layout();
  layout.max_rate_hz = 1000;  // the arithmetic above is per 1 kHz tick
  movie::TactileMovie movie = movie::testing::sine_movie(layout, 1000, 20, 0);
  for (std::int32_t f = 10; f < 20; ++f) {
    for (float& v : movie.frame(f)) v = 40;
  }
  PlayOptions options;
  options.ramp_s = 0;
  PlaybackReport r;
  const movie::TactileMovie out = render_through_device(movie, device_for(layout), options, &r);
  EXPECT_GT(r.slew_limited_samples, 0);
  EXPECT_FLOAT_EQ(out.frame(9)[0], 0);
  EXPECT_FLOAT_EQ(out.frame(10)[0], 20);
  EXPECT_FLOAT_EQ(out.frame(11)[0], 40);
}

void expect_refused(const movie::TactileMovie& movie, const EmulatedDeviceOptions& o,
                    const std::string& words) {
  EmulatedDevice device(o);
  try {
    play_movie(movie, device);
    FAIL() << "played; expected a refusal about " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr(words));
  }
  EXPECT_EQ(device.status().frames_received, 0u);  // refused before anything was sent
}

TEST(Player, RefusesMoviesTheDeviceCannotPlay) {
  const auto stress = device_for(movie::stress_layout());
  expect_refused(movie::testing::sine_movie(movie::latero_layout(), 700, 10, 10), stress,
                 "is 8 x 8 contactors but device");
  expect_refused(movie::testing::sine_movie(movie::stress2_layout(), 1000, 10, 10),
                 device_for(movie::latero_layout()), "pitch 1.2 x 1.4 mm");
  expect_refused(movie::testing::sine_movie(movie::stress_layout(), 1000, 10, 10), stress,
                 "rate 1000 Hz exceeds the device maximum 700 Hz");
  expect_refused(movie::testing::sine_movie(movie::stress_layout(), 699.5, 10, 10), stress,
                 "movie rate 699.5 Hz is not playable: devices play a whole number of hertz");
  expect_refused(movie::testing::sine_movie(movie::stress_layout(), 700, 10, 60), stress,
                 "outside the device range [-50, 50] um");
}

TEST(Player, RealTimeClockPlaysAtTheDeviceRate) {
  const movie::TactileMovie movie =
      movie::testing::sine_movie(movie::stress_layout(), 700, 140, 30);  // 0.2 s
  EmulatedDeviceOptions o = device_for(movie.layout);
  o.clock = EmulatedClock::real_time;
  EmulatedDevice device(o);
  const PlaybackReport r = play_movie(movie, device);
  EXPECT_EQ(r.frames_played, r.frames_sent);
  const double expected_s = static_cast<double>(r.frames_sent) / 700;  // 0.3 s with ramps
  EXPECT_GT(r.wall_s, expected_s * 0.9);
  EXPECT_LT(r.wall_s, expected_s + 0.5);
  // Half a FIFO (32 frames = 46 ms) absorbs ordinary scheduling delays.
  EXPECT_EQ(r.underruns, 0);
}

// Where the contactors stand is read from the firmware's outputs: away from rest while a frame
// holds them there, back at 0 once a stop's slew-limited ramp has run.
TEST(EmulatedDevice, SaysHowFarFromRestItsContactorsStand) {
  EmulatedDeviceOptions o = device_for(movie::stress_layout());
  o.record_outputs = false;  // as a live session runs it
  EmulatedDevice device(o);
  EXPECT_EQ(device.farthest_from_rest_um(), 0.0f);
  device.start(700);
  std::vector<float> frame(100, 0);
  frame[37] = -30;
  for (std::uint32_t seq = 0; seq < 40; ++seq)
    ASSERT_TRUE(device.send_frame(encode_frame(frame, seq)));
  device.wait(std::chrono::milliseconds(50));
  EXPECT_EQ(device.farthest_from_rest_um(), 30.0f);
  device.stop();
  // One tick after the stop: on its way (the slew limit moves 28.6 um a tick at 700 Hz), not
  // still at 30 um and not at rest.
  device.wait(std::chrono::nanoseconds(1'000'000'000 / 700 + 1));
  EXPECT_GT(device.farthest_from_rest_um(), 0.0f);
  EXPECT_LT(device.farthest_from_rest_um(), 30.0f);
  device.wait(std::chrono::seconds(1));
  EXPECT_EQ(device.farthest_from_rest_um(), 0.0f);
}

TEST(EmulatedDevice, CountsMalformedFramesAndNeverPlaysThem) {
  EmulatedDevice device(device_for(movie::stress_layout()));
  device.start(700);
  std::vector<float> frame(100, 5);
  auto good = encode_frame(frame, 0);
  std::vector<float> poison(100, 44);
  auto bad_crc = encode_frame(poison, 1);
  bad_crc[20] ^= 0xFF;
  auto short_frame = encode_frame(poison, 1);
  short_frame.resize(short_frame.size() - 2);
  auto repeated = encode_frame(poison, 0);
  EXPECT_TRUE(device.send_frame(good));
  EXPECT_TRUE(device.send_frame(bad_crc));  // delivered; the device is the judge
  EXPECT_TRUE(device.send_frame(short_frame));
  EXPECT_TRUE(device.send_frame(repeated));
  device.wait(std::chrono::milliseconds(50));
  const DeviceStatus s = device.status();
  EXPECT_EQ(s.frames_played, 1u);
  EXPECT_EQ(s.malformed, 3u);
  EXPECT_EQ(s.rejected_by_reason.at("bad_checksum"), 1u);
  EXPECT_EQ(s.rejected_by_reason.at("bad_length"), 1u);
  EXPECT_EQ(s.rejected_by_reason.at("bad_sequence"), 1u);
  const movie::TactileMovie out = device.recording();
  for (float v : out.deflection_um) EXPECT_LE(v, 5.0f);
}

TEST(EmulatedDevice, SimulatedClockRunsOneTickPerPeriod) {
  EmulatedDevice device(device_for(movie::stress_layout()));
  device.start(700);
  // 1/700 s rounded up to whole nanoseconds: every wait covers exactly one more tick.
  const std::chrono::nanoseconds period(1'000'000'000 / 700 + 1);
  for (std::uint64_t i = 1; i <= 700; ++i) {
    device.wait(period);
    ASSERT_EQ(device.status().ticks, i);
  }
  EXPECT_NEAR(device.now_s(), 1.0, 1e-5);
}

TEST(EmulatedDevice, WatchdogBringsTheOutputsHome) {
  movie::Layout layout = movie::latero_layout();
  layout.max_rate_hz = 1000;  // the tick counts below are at 1 kHz
  EmulatedDevice device(device_for(layout));
  device.start(1000);
  std::vector<float> frame(64, 90);
  for (std::uint32_t s = 0; s < 10; ++s) ASSERT_TRUE(device.send_frame(encode_frame(frame, s)));
  device.wait(std::chrono::milliseconds(30));  // 10 frames, then 20 ms of silence
  const movie::TactileMovie out = device.recording();
  ASSERT_EQ(out.frame_count, 30);
  EXPECT_FLOAT_EQ(out.frame(9)[0], 90);
  EXPECT_FLOAT_EQ(out.frame(29)[0], 0);
  EXPECT_EQ(device.status().watchdog_trips, 1u);
}

TEST(EmulatedDevice, RecordsTheFirmwareStateAfterEveryTick) {
  // STReSS: +-50 um; 20 mm/s at 700 Hz is 285 units (28.5 um) per tick.
  EmulatedDevice device(device_for(movie::stress_layout()));
  device.start(700);
  std::vector<float> frame(100, 80);  // beyond the range: every sample clamped to 50 um
  for (std::uint32_t s = 0; s < 10; ++s) ASSERT_TRUE(device.send_frame(encode_frame(frame, s)));
  device.wait(std::chrono::milliseconds(30));
  const std::vector<DeviceTick> states = device.recorded_states();
  ASSERT_EQ(static_cast<std::int64_t>(states.size()), device.recorded_ticks());
  ASSERT_EQ(states.size(), 21u);  // 30 ms at 700 Hz
  EXPECT_TRUE(states[0].streaming);
  EXPECT_EQ(states[0].clamped_samples, 100u);
  EXPECT_EQ(states[0].fifo_fill, 9u);  // 10 sent, one played
  // 0 -> 28.5 -> 50 um: the first step is cut to the slew limit, the second is not.
  EXPECT_EQ(states[9].slew_limited_samples, 100u);
  EXPECT_EQ(states[9].clamped_samples, 1000u);
  EXPECT_EQ(states[9].watchdog_trips, 0u);
  // Then silence: underruns until the 5 ms watchdog trips, and the device idles at neutral.
  EXPECT_EQ(states.back().watchdog_trips, 1u);
  EXPECT_FALSE(states.back().streaming);
  EXPECT_TRUE(states.back().started);
  EXPECT_GE(states.back().underruns, 1u);
  EXPECT_LE(states.back().underruns, 5u);
  EXPECT_EQ(states.back().clamped_samples, 1000u);
}

}  // namespace
}  // namespace tactile::display

namespace tactile::display {
namespace {

// Wraps a simulated-clock device and, once, lets `hiccup` of device time pass while the host
// is "busy" (as if the host process had been descheduled).
class HiccupTransport final : public Transport {
 public:
  HiccupTransport(EmulatedDevice& device, int at_wait, std::chrono::milliseconds hiccup)
      : device_(device), at_wait_(at_wait), hiccup_(hiccup) {}
  DeviceInfo info() override { return device_.info(); }
  void start(double rate_hz) override { device_.start(rate_hz); }
  void stop() override { device_.stop(); }
  bool send_frame(std::span<const std::uint8_t> f) override { return device_.send_frame(f); }
  DeviceStatus status() override { return device_.status(); }
  void wait(std::chrono::nanoseconds d) override {
    device_.wait(++waits_ == at_wait_ ? std::chrono::nanoseconds(hiccup_) : d);
  }

 private:
  EmulatedDevice& device_;
  int waits_ = 0;
  int at_wait_;
  std::chrono::milliseconds hiccup_;
};

PlaybackReport play_with_hiccup(std::chrono::milliseconds hiccup) {
  const movie::TactileMovie movie =
      movie::testing::sine_movie(movie::stress_layout(), 700, 1400, 30);
  EmulatedDevice device(device_for(movie.layout));
  HiccupTransport link(device, 1000, hiccup);
  return play_movie(movie, link);
}

TEST(Player, HostHiccupShorterThanHalfTheFifoCostsNothing) {
  // Half of the 64-frame FIFO at 700 Hz is 45.7 ms of frames queued.
  const PlaybackReport ok = play_with_hiccup(std::chrono::milliseconds(40));
  EXPECT_EQ(ok.underruns, 0);
  EXPECT_EQ(ok.frames_played, ok.frames_sent);
  const PlaybackReport late = play_with_hiccup(std::chrono::milliseconds(60));
  EXPECT_GT(late.underruns, 0);  // the FIFO ran dry: counted, not hidden
  EXPECT_LT(late.underruns, 60 * 700 / 1000);
  EXPECT_EQ(late.frames_played, late.frames_sent);  // and nothing was lost
}

TEST(Player, LoopsRepeatTheMovieBetweenOneRampInAndOneRampOut) {
  const movie::TactileMovie movie = movie::testing::sine_movie(movie::stress_layout(), 700, 70, 20);
  PlayOptions o;
  o.loops = 3;
  PlaybackReport r;
  const movie::TactileMovie out = render_through_device(movie, device_for(movie.layout), o, &r);
  EXPECT_EQ(r.movie_frames, 210);
  EXPECT_EQ(r.frames_played, 210 + r.ramp_frames);
  const auto ramp_in = static_cast<std::int32_t>(r.ramp_frames / 2);
  for (std::int32_t f = 0; f < 210; ++f) {
    ASSERT_NEAR(out.frame(ramp_in + f)[17], movie.frame(f % 70)[17], 0.051) << f;
  }
}

}  // namespace
}  // namespace tactile::display

namespace tactile::display {
namespace {

TEST(EmulatedDevice, ReportsItsGeometryThroughTheControlReply) {
  movie::Layout l = movie::latero_layout();
  l.axis = movie::DeflectionAxis::y;
  EmulatedDevice device(device_for(l));
  const DeviceInfo info = device.info();
  EXPECT_EQ(info.backend, Backend::emulated);
  EXPECT_EQ(info.layout.name, "latero");
  EXPECT_EQ(info.layout.rows, 8);
  EXPECT_DOUBLE_EQ(info.layout.pitch_y_mm, 1.6125);  // exact through nanometres
  EXPECT_DOUBLE_EQ(info.layout.contactor_height_mm, 1.4);
  EXPECT_EQ(info.layout.axis, movie::DeflectionAxis::y);
  EXPECT_DOUBLE_EQ(info.layout.deflection_max_um, 100);
  EXPECT_DOUBLE_EQ(info.layout.max_rate_hz, 750);
  EXPECT_DOUBLE_EQ(info.max_slew_um_per_s, 20000);
  EXPECT_DOUBLE_EQ(info.watchdog_timeout_s, 0.005);
  EXPECT_EQ(info.fifo_capacity_frames, 64u);
  EXPECT_FALSE(info.firmware_version.empty());
}

TEST(ControlCodec, MalformedRepliesAreTransportErrors) {
  const std::vector<std::uint8_t> short_reply(10, 1);
  try {
    decode_device_info(short_reply, Backend::libusb, "bench display", "S1", "stress");
    FAIL() << "accepted";
  } catch (const TransportError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bench display"));
    EXPECT_THAT(e.what(), HasSubstr("bad_length"));
  }
  EXPECT_THROW(decode_device_status(short_reply), TransportError);
}

}  // namespace
}  // namespace tactile::display

namespace tactile::display {
namespace {

// Passes frames to a device and, once `after` frames have gone, makes `stop_fd` readable, as
// a SIGINT arriving mid-play makes a StopSignals descriptor readable.
class StopAfterTransport final : public Transport {
 public:
  StopAfterTransport(EmulatedDevice& device, int after, int stop_write_fd)
      : device_(device), after_(after), stop_write_fd_(stop_write_fd) {}
  DeviceInfo info() override { return device_.info(); }
  void start(double rate_hz) override { device_.start(rate_hz); }
  void stop() override { device_.stop(); }
  bool send_frame(std::span<const std::uint8_t> f) override {
    const bool taken = device_.send_frame(f);
    if (taken && ++sent_ == after_) {
      EXPECT_EQ(::write(stop_write_fd_, "x", 1), 1);
    }
    return taken;
  }
  DeviceStatus status() override { return device_.status(); }
  void wait(std::chrono::nanoseconds d) override { device_.wait(d); }

 private:
  EmulatedDevice& device_;
  int sent_ = 0;
  int after_;
  int stop_write_fd_;
};

TEST(Player, StopRequestRampsEveryContactorToRestAtTheSlewLimit) {
  // Every contactor held at +45 um, a slow slew limit (2 mm/s = 2.857 um per tick at 700 Hz)
  // so that the way back to rest takes many ticks and each of them can be checked.
  movie::TactileMovie movie = movie::testing::sine_movie(movie::stress_layout(), 700, 2000, 0);
  std::fill(movie.deflection_um.begin(), movie.deflection_um.end(), 45.0f);
  EmulatedDeviceOptions o = device_for(movie.layout);
  o.max_slew_um_per_s = 2000;
  o.record_outputs = true;
  EmulatedDevice device(o);
  int pipe_fds[2];
  ASSERT_EQ(::pipe(pipe_fds), 0);
  StopAfterTransport link(device, 300, pipe_fds[1]);
  PlayOptions options;
  options.stop_fd = pipe_fds[0];
  const PlaybackReport r = play_movie(movie, link, options);
  ::close(pipe_fds[0]);
  ::close(pipe_fds[1]);
  EXPECT_TRUE(r.interrupted);
  EXPECT_THAT(format_playback_report(r), HasSubstr("stopped     by a stop request"));
  // Stopped at the next poll: at most a FIFO's worth more than the 300th frame was sent, and
  // the frames still queued were dropped, not played.
  const auto capacity = static_cast<std::int64_t>(device.info().fifo_capacity_frames);
  EXPECT_GE(r.frames_sent, 300);
  EXPECT_LE(r.frames_sent, 300 + capacity);
  EXPECT_LT(r.frames_played, r.frames_sent);
  EXPECT_EQ(device.status().fifo_fill, 0u);

  const movie::TactileMovie out = device.recording();
  ASSERT_GT(out.frame_count, 2);
  const double per_tick_um = 2000.0 / 700.0;
  // Where the stop found the outputs: at the movie's 45 um, not already at rest.
  const auto played = static_cast<std::int32_t>(r.frames_played);
  for (const float v : out.frame(played - 1)) EXPECT_NEAR(v, 45, 0.05);
  // From there to rest: never faster than the slew limit (0.1 um quantisation), ending at 0.
  std::int32_t ramp_ticks = 0;
  for (std::int32_t f = played; f < out.frame_count; ++f) {
    const auto a = out.frame(f - 1);
    const auto b = out.frame(f);
    if (b[0] != a[0]) ++ramp_ticks;
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_LE(std::abs(b[i] - a[i]), per_tick_um + 0.1) << "tick " << f << " contactor " << i;
    }
  }
  for (const float v : out.frame(out.frame_count - 1)) EXPECT_EQ(v, 0);
  EXPECT_GE(ramp_ticks, static_cast<int>(std::floor(45 / per_tick_um)));
}

}  // namespace
}  // namespace tactile::display
