#pragma once
// The player through a USB transport, checked the same way for every back end: a 0.2 s STReSS
// movie at 700 Hz reaches the device whole (ramps included), none of it malformed.

#include <gtest/gtest.h>

#include <cstdio>

#include "../movie/test_movies.hpp"
#include "tactile/display/player.hpp"

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

}  // namespace tactile::display::testing
