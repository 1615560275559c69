// play_anywhere's choice among the back ends a program offers: the core library plays headless
// by itself and takes displays and the window only as PlayBackends.
#include "tactile/display/play_anywhere.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../movie/test_movies.hpp"
#include "tactile/display/emulated_device.hpp"

namespace tactile::display {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

movie::TactileMovie small_movie() {
  return movie::testing::sine_movie(movie::stress_layout(), 700, 70, 20);
}

DeviceDescription display_at(const std::string& path) {
  DeviceDescription d;
  d.backend = Backend::libusb;
  d.path = path;
  d.accessible = true;
  return d;
}

TEST(PlayAnywhere, WithNoBackEndsPlaysHeadlessAndSaysNoWindowWasPossible) {
  std::string said;
  const PlayResult r = play_anywhere(small_movie(), ResolvedPlay{},
                                     [&](const std::string& text) { said += text; }, {});
  EXPECT_EQ(r.target, PlaybackTarget::headless);
  ASSERT_TRUE(r.report);
  EXPECT_EQ(r.report->movie_frames, 70);
  EXPECT_EQ(r.final_max_um, 0);
  EXPECT_THAT(said, HasSubstr("no emulator window in this program"));
  EXPECT_THAT(said, Not(HasSubstr("no screen")));
}

TEST(PlayAnywhere, AnOfferedDisplayTakesTheMovieThroughTheBackEndThatOpensIt) {
  int opened = 0;
  int screens_asked = 0;
  PlayBackends backends;
  backends.list_devices = [] { return std::vector<DeviceDescription>{display_at("1:7")}; };
  backends.open_device = [&](const DeviceDescription& d) -> std::unique_ptr<Transport> {
    EXPECT_EQ(d.path, "1:7");
    ++opened;
    EmulatedDeviceOptions o;
    o.layout = movie::stress_layout();
    return std::make_unique<EmulatedDevice>(o);
  };
  backends.screen = [&] {
    ++screens_asked;
    return true;
  };
  backends.play_in_window = [](const movie::TactileMovie&, const ResolvedPlay&, const Say&,
                               PlayResult&) { ADD_FAILURE() << "the window opened"; };
  const PlayResult r = play_anywhere(
      small_movie(), ResolvedPlay{}, [](const std::string&) {}, backends);
  EXPECT_EQ(r.target, PlaybackTarget::device);
  EXPECT_EQ(opened, 1);
  EXPECT_EQ(screens_asked, 0);
  ASSERT_TRUE(r.device && r.report);
  EXPECT_EQ(r.device->path, "1:7");
  EXPECT_EQ(r.report->movie_frames, 70);
}

TEST(PlayAnywhere, TheWindowTakesTheMovieOnlyWhenItsBackEndFindsAScreen) {
  int windows = 0;
  bool screen = true;
  PlayBackends backends;
  backends.screen = [&] { return screen; };
  backends.play_in_window = [&](const movie::TactileMovie& m, const ResolvedPlay&, const Say&,
                                PlayResult&) {
    EXPECT_EQ(m.frame_count, 70);
    ++windows;
  };
  std::string said;
  const auto say = [&](const std::string& text) { said += text; };
  EXPECT_EQ(play_anywhere(small_movie(), ResolvedPlay{}, say, backends).target,
            PlaybackTarget::window);
  EXPECT_EQ(windows, 1);
  EXPECT_THAT(said, HasSubstr("opening the emulator window"));
  screen = false;
  said.clear();
  EXPECT_EQ(play_anywhere(small_movie(), ResolvedPlay{}, say, backends).target,
            PlaybackTarget::headless);
  EXPECT_EQ(windows, 1);
  EXPECT_THAT(said, HasSubstr("no display attached and no screen"));
  // Headless asked for: neither back end is consulted.
  screen = true;
  ResolvedPlay headless;
  headless.headless = true;
  EXPECT_EQ(play_anywhere(small_movie(), headless, say, backends).target, PlaybackTarget::headless);
  EXPECT_EQ(windows, 1);
}

}  // namespace
}  // namespace tactile::display
