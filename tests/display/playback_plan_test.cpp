// Where `tactile play` sends a movie, decided from what is attached and whether a screen exists.

#include "tactile/display/playback_plan.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace tactile::display {
namespace {

using ::testing::HasSubstr;

DeviceDescription device(Backend backend, const std::string& path, bool accessible) {
  DeviceDescription d;
  d.backend = backend;
  d.path = path;
  d.accessible = accessible;
  return d;
}

TEST(PlaybackPlan, PrefersTheVendorInterfaceOfAnOpenableDisplay) {
  // The HID interface is listed first, as hidraw nodes may be; bulk still wins.
  const std::vector<DeviceDescription> both = {device(Backend::hidapi, "/dev/hidraw0", true),
                                               device(Backend::libusb, "1:4", true)};
  ASSERT_TRUE(pick_device(both));
  EXPECT_EQ(pick_device(both)->path, "1:4");
  // A vendor interface that cannot be opened does not hide an openable HID interface.
  const std::vector<DeviceDescription> hid_only = {device(Backend::libusb, "1:4", false),
                                                   device(Backend::hidapi, "/dev/hidraw0", true)};
  EXPECT_EQ(pick_device(hid_only)->backend, Backend::hidapi);
  EXPECT_FALSE(pick_device({device(Backend::libusb, "1:4", false)}));
  EXPECT_FALSE(pick_device({}));
}

TEST(PlaybackPlan, ADisplayTakesTheMovieWithoutAskingForAScreen) {
  int asked = 0;
  const auto screen = [&] {
    ++asked;
    return true;
  };
  const auto plan = plan_playback(false, {device(Backend::libusb, "1:4", true)}, screen);
  EXPECT_EQ(plan.target, PlaybackTarget::device);
  ASSERT_TRUE(plan.device);
  EXPECT_EQ(plan.device->path, "1:4");
  EXPECT_FALSE(plan.unopenable);
  EXPECT_EQ(asked, 0);
}

TEST(PlaybackPlan, WithoutAnOpenableDisplayTheWindowIfThereIsAScreenElseHeadless) {
  const std::vector<DeviceDescription> locked = {device(Backend::libusb, "1:4", false)};
  const auto window = plan_playback(false, locked, [] { return true; });
  EXPECT_EQ(window.target, PlaybackTarget::window);
  EXPECT_FALSE(window.device);
  ASSERT_TRUE(window.unopenable);  // the user is told a display is there
  EXPECT_EQ(window.unopenable->path, "1:4");
  const auto headless = plan_playback(false, {}, [] { return false; });
  EXPECT_EQ(headless.target, PlaybackTarget::headless);
  EXPECT_FALSE(headless.unopenable);
}

TEST(PlaybackPlan, HeadlessIgnoresDisplaysAndScreens) {
  bool asked = false;
  const auto plan = plan_playback(true, {device(Backend::libusb, "1:4", true)}, [&] {
    asked = true;
    return true;
  });
  EXPECT_EQ(plan.target, PlaybackTarget::headless);
  EXPECT_FALSE(plan.device);
  EXPECT_FALSE(plan.unopenable);
  EXPECT_FALSE(asked);
}

TEST(PlaybackPlan, ReportLineGivesTheCounts) {
  PlaybackReport r;
  r.frames_played = 1400;
  r.movie_frames = 1330;
  r.ramp_frames = 70;
  r.rate_hz = 700;
  r.duration_s = 2;
  r.wall_s = 2.0005;
  r.underruns = 3;
  r.malformed = 0;
  r.clamped_samples = 12;
  r.slew_limited_samples = 5;
  const std::string line = playback_summary_line(r);
  // The movie's own length beside the ramp, so that it reads as `info` and `map` count it.
  EXPECT_THAT(line, HasSubstr("1400 frames played at 700 Hz (of 1330 movie frames + 70 frames of "
                              "ramp from and to rest;"));
  EXPECT_THAT(line, HasSubstr("2.00 s device time"));
  EXPECT_THAT(line, HasSubstr("3 underruns"));
  EXPECT_THAT(line, HasSubstr("12 samples clamped, 5 slew-limited"));
  EXPECT_EQ(line.back(), '\n');
}

}  // namespace
}  // namespace tactile::display
