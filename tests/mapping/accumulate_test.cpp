// Strain accumulated along tracks: exact answers for a homogeneous stretch of sliding skin.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "tactile/mapping/accumulate.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/mapping/strain_field.hpp"

namespace tactile::mapping {
namespace {

using ::testing::HasSubstr;

// Skin landmarks on a jitter-free 0.5 mm grid; at frame f every landmark X is at
// X + (rate * f * X_x + slide * f, 0): a stretch along x growing by `rate` per frame on skin that
// slides by `slide` mm per frame. Tracks only: no StrainFrames are needed to accumulate.
capture::StrainMovie stretching_slide(double rate, double slide_mm, int frames) {
  capture::StrainMovie movie;
  movie.frame_rate_hz = 60;
  movie.camera_frame_count = frames;
  movie.provenance.input = "stretching slide";
  int id = 0;
  for (int j = 0; j < 12; ++j) {
    for (int i = 0; i < 12; ++i, ++id) {
      const double x = 0.5 * i, y = 0.5 * j;
      // Track id 5 dies after frame 3 and track 7 starts at frame 2: the accumulated frames must
      // keep only landmarks alive at both ends.
      for (int f = (id == 7 ? 2 : 0); f < (id == 5 ? 4 : frames); ++f) {
        movie.tracks.push_back({id, f, {}, 0, 0, x + rate * f * x + slide_mm * f, y});
      }
    }
  }
  return movie;
}

TEST(AccumulateAlongTracks, GivesTheStrainFromTheReferenceFrameWhereverTheSkinSlid) {
  const double rate = 0.002;
  const auto movie = stretching_slide(rate, 0.3, 10);
  AccumulateOptions options;
  options.reference_frame = 2;
  const auto acc = accumulate_along_tracks(movie, options);
  ASSERT_EQ(acc.frames.size(), 7u);  // frames 3..9
  for (const auto& sf : acc.frames) {
    EXPECT_EQ(sf.frame_from, 2);
    EXPECT_DOUBLE_EQ(sf.t_s, sf.frame_to / 60.0);
    // Track 7 was born at the reference frame and stays; track 5 died at frame 3.
    const auto has = [&](int id) {
      for (const auto& p : sf.points_from) {
        if (p.track_id == id) return true;
      }
      return false;
    };
    EXPECT_TRUE(has(7));
    EXPECT_EQ(has(5), sf.frame_to <= 3);
    // x(f) / x(2) = (1 + rate f) / (1 + rate 2) along x, up to the slide which cancels.
    const double want = (1 + rate * sf.frame_to) / (1 + rate * 2) - 1;
    for (const auto& e : sf.edges) {
      if (std::abs(e.length_from_mm - 0.5 * (1 + 2 * rate)) < 1e-9) {
        EXPECT_NEAR(e.rel_change, want, 1e-12);  // horizontal edges: exact
      }
    }
    const auto field = build_strain_field(sf);
    // Sample inside the reference positions (where the skin was at frame 2).
    const auto s = sample(field, 0.6 + 2.5, 2.6);
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(s->exx, want, 1e-4);  // small-strain tensor of a finite stretch: O(e^2) off
    EXPECT_NEAR(s->eyy, 0, 1e-4);
    EXPECT_NEAR(s->exy, 0, 1e-4);
  }
}

TEST(AccumulateAlongTracks, DefaultReferenceIsTheFirstStrainFrame) {
  auto movie = stretching_slide(0.001, 0.1, 6);
  capture::StrainFrame first;
  first.frame_from = 1;
  first.frame_to = 2;
  first.t_s = 2 / 60.0;
  movie.frames.push_back(first);
  const auto acc = accumulate_along_tracks(movie);
  ASSERT_FALSE(acc.frames.empty());
  EXPECT_EQ(acc.frames.front().frame_from, 1);
  EXPECT_EQ(acc.frames.front().frame_to, 2);
}

TEST(AccumulateAlongTracks, RefusesMoviesWithoutTracksAndBadReferences) {
  capture::StrainMovie empty;
  empty.provenance.input = "no tracks here";
  try {
    accumulate_along_tracks(empty);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("no tracks"));
    EXPECT_THAT(e.what(), HasSubstr("no tracks here"));
  }
  const auto movie = stretching_slide(0.001, 0.1, 6);
  AccumulateOptions options;
  options.reference_frame = 6;
  try {
    accumulate_along_tracks(movie, options);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("reference frame 6 outside"));
  }
}

}  // namespace
}  // namespace tactile::mapping
