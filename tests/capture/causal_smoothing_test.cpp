// The causal smoother of tracks: exact on the motions its polynomial can follow, quieter than the
// measured step on noise, and never looking past the step it smooths.

#include "tactile/capture/causal_smoothing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace tactile::capture {
namespace {

// A step as AlignmentTracker::last_step gives it: a track of two frames.
Track step_of(std::int32_t id, double x0, double y0, double x1, double y1) {
  Track t;
  t.id = id;
  t.x_px = {x0, x1};
  t.y_px = {y0, y1};
  return t;
}

double quadratic_x(double t) {
  return 10 + 2.5 * t + 0.3 * t * t;
}
double quadratic_y(double t) {
  return -4 + 0.7 * t - 0.05 * t * t;
}

// One step of track `id` from frame a into frame b, measured on the quadratic path plus `noise`.
Track step_on_path(std::int32_t id, std::int64_t a, std::int64_t b, double noise_a = 0,
                   double noise_b = 0) {
  const auto ta = static_cast<double>(a);
  const auto tb = static_cast<double>(b);
  return step_of(id, quadratic_x(ta) + noise_a, quadratic_y(ta), quadratic_x(tb) + noise_b,
                 quadratic_y(tb));
}

TEST(CausalSmoothing, AQuadraticFitFollowsAQuadraticMotionExactlyDroppedFramesIncluded) {
  CausalTrackSmoother smoother({.window_frames = 5, .degree = 2});
  // Frames 0..9 with frames 4 and 7 dropped: a step may span two camera frames.
  const std::vector<std::int64_t> frames{0, 1, 2, 3, 5, 6, 8, 9};
  for (std::size_t i = 1; i < frames.size(); ++i) {
    std::vector<Track> steps{step_on_path(7, frames[i - 1], frames[i])};
    smoother.smooth(frames[i - 1], frames[i], steps);
    const Track exact = step_on_path(7, frames[i - 1], frames[i]);
    EXPECT_NEAR(steps[0].x_px[0], exact.x_px[0], 1e-9) << "into frame " << frames[i];
    EXPECT_NEAR(steps[0].x_px[1], exact.x_px[1], 1e-9) << "into frame " << frames[i];
    EXPECT_NEAR(steps[0].y_px[0], exact.y_px[0], 1e-9) << "into frame " << frames[i];
    EXPECT_NEAR(steps[0].y_px[1], exact.y_px[1], 1e-9) << "into frame " << frames[i];
  }
}

TEST(CausalSmoothing, ATrackSeenInTooFewFramesKeepsItsMeasuredStep) {
  CausalTrackSmoother smoother({.window_frames = 5, .degree = 2});
  // Noise on the second frame only: with two positions the fit is not made, with four (the
  // quadratic's three terms and one more) it is.
  std::vector<Track> first{step_on_path(1, 0, 1, 0, 0.5)};
  smoother.smooth(0, 1, first);
  EXPECT_DOUBLE_EQ(first[0].x_px[1], quadratic_x(1) + 0.5);
  std::vector<Track> second{step_on_path(1, 1, 2, 0.5, 0)};
  smoother.smooth(1, 2, second);
  EXPECT_DOUBLE_EQ(second[0].x_px[0], quadratic_x(1) + 0.5);
  std::vector<Track> third{step_on_path(1, 2, 3)};
  smoother.smooth(2, 3, third);
  EXPECT_NE(third[0].x_px[0], quadratic_x(2));
}

TEST(CausalSmoothing, ATrackMissingFromAFrameStartsAgain) {
  CausalTrackSmoother smoother({.window_frames = 5, .degree = 2});
  for (std::int64_t f = 1; f <= 4; ++f) {
    std::vector<Track> steps{step_on_path(3, f - 1, f, 0, f == 2 ? 1.0 : 0.0)};
    smoother.smooth(f - 1, f, steps);
  }
  // Frame 5 without track 3: it is forgotten, so its step into 6 is its first again, as measured.
  std::vector<Track> none;
  smoother.smooth(4, 5, none);
  std::vector<Track> back{step_on_path(3, 5, 6, 0, 0.25)};
  smoother.smooth(5, 6, back);
  EXPECT_DOUBLE_EQ(back[0].x_px[1], quadratic_x(6) + 0.25);
}

TEST(CausalSmoothing, OnWhiteNoiseTheStepVariesAsLittleAsItsLeastSquaresWeightsSay) {
  // A still point measured with independent errors of 1 px: the measured step varies by 2 px^2.
  // A least-squares quadratic over frames -4..0, read at 0 and -1, gives the step as the
  // positions weighted (16, -22, -30, -8, 44) / 70, whose squares sum to 26/35 = 0.743 px^2.
  CausalTrackSmoother smoother({.window_frames = 5, .degree = 2});
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0, 1);
  double previous = noise(rng);
  double sum_sq = 0;
  int n = 0;
  for (std::int64_t f = 1; f <= 20000; ++f) {
    const double now = noise(rng);
    std::vector<Track> steps{step_of(0, previous, 0, now, 0)};
    smoother.smooth(f - 1, f, steps);
    if (f >= 5) {
      const double d = steps[0].x_px[1] - steps[0].x_px[0];
      sum_sq += d * d;
      ++n;
    }
    previous = now;
  }
  EXPECT_NEAR(sum_sq / n, 26.0 / 35.0, 0.03);
}

// The guard the capture uses (a window may not move the median track by more than this, RMS).
constexpr double kResidualPx = RefineParams{}.max_smoothing_residual_px;

// A grid of 25 x 25 tracks 20 px apart over `frames` frames, each moved along x by
// motion(x, frame) and measured with independent errors of noise_px.
std::vector<Track> grid_tracks(int frames, double noise_px,
                               const std::function<double(double, int)>& motion) {
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0, noise_px);
  std::vector<Track> tracks;
  for (int r = 0; r < 25; ++r) {
    for (int c = 0; c < 25; ++c) {
      Track t;
      t.id = static_cast<std::int32_t>(tracks.size());
      const double x = 20.0 * c, y = 20.0 * r;
      for (int f = 0; f < frames; ++f) {
        t.x_px.push_back(x + motion(x, f) + noise(rng));
        t.y_px.push_back(y + noise(rng));
      }
      tracks.push_back(std::move(t));
    }
  }
  return tracks;
}

TEST(CausalSmoothing, OnStillSkinTheLongestWindowIsChosen) {
  // Nothing changes between neighbours but the noise: every longer window only removes more.
  const auto tracks = grid_tracks(60, 0.05, [](double, int) { return 0.0; });
  EXPECT_EQ(causal_smoothing_that_fits(tracks, 2, kResidualPx), kCausalWindows.back());
}

TEST(CausalSmoothing, AStrainThatChangesEverySixFramesIsNotSmoothedAway) {
  // Neighbours 20 px apart move 0.5 px out of phase (a strain of a few percent) with a period of
  // six frames, under noise of 0.01 px: a quadratic over four frames or more, looking back, lags
  // such a change by a large part of its size, far more than the noise it removes.
  const auto tracks = grid_tracks(60, 0.01, [](double x, int f) {
    return 3.0 * std::sin(2 * std::numbers::pi * f / 6.0 + x / 120.0);
  });
  EXPECT_EQ(causal_smoothing_that_fits(tracks, 2, kResidualPx), 0);
}

TEST(CausalSmoothing, ASlowStrainUnderNoiseGetsAWindowBetweenTheEnds) {
  // The same strain over 40 frames a period under noise of 0.05 px: some smoothing pays, the
  // longest window lags too much (a quadratic over 24 frames spans more than half a period).
  const auto tracks = grid_tracks(60, 0.05, [](double x, int f) {
    return 3.0 * std::sin(2 * std::numbers::pi * f / 40.0 + x / 120.0);
  });
  const int w = causal_smoothing_that_fits(tracks, 2, kResidualPx);
  EXPECT_GT(w, 0);
  EXPECT_LT(w, kCausalWindows.back());
}

TEST(CausalSmoothing, AChosenWindowIsChosenFromTheTracksAsTheyCome) {
  CausalTrackSmoother smoother({});
  const auto tracks = grid_tracks(60, 0.05, [](double, int) { return 0.0; });
  int choices = 0;
  for (std::int64_t f = 1; f < 60; ++f) {
    std::vector<Track> steps;
    for (const auto& t : tracks) {
      const auto k = static_cast<std::size_t>(f);
      steps.push_back(step_of(t.id, t.x_px[k - 1], t.y_px[k - 1], t.x_px[k], t.y_px[k]));
    }
    smoother.smooth(f - 1, f, steps);
    if (smoother.choice_due()) {
      ++choices;
      smoother.set_window(
          causal_smoothing_that_fits(smoother.tracks_to_choose_by(), 2, kResidualPx));
    }
    // None before the tracks are long enough to choose by, then the longest (still skin).
    EXPECT_EQ(smoother.window_frames(), f < kCausalChoiceFrames ? 0 : kCausalWindows.back())
        << "after frame " << f;
  }
  EXPECT_EQ(choices, 2);  // at 25 and 55 frames of steps
}

TEST(CausalSmoothing, AStepOfOtherThanTwoPositionsIsRefusedNamingTheTrack) {
  CausalTrackSmoother smoother({});
  std::vector<Track> steps{step_of(12, 0, 0, 1, 1)};
  steps[0].x_px.push_back(2);
  steps[0].y_px.push_back(2);
  try {
    smoother.smooth(0, 1, steps);
    FAIL() << "accepted a track of three positions";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("track 12 has 3 positions"), std::string::npos)
        << e.what();
  }
}

TEST(CausalSmoothing, AWindowOutOfRangeIsRefusedNamingIt) {
  for (const CausalSmoothing bad : {CausalSmoothing{.window_frames = 31, .degree = 2},
                                    CausalSmoothing{.window_frames = -2, .degree = 2},
                                    CausalSmoothing{.window_frames = 3, .degree = 2},
                                    CausalSmoothing{.window_frames = 5, .degree = 3},
                                    CausalSmoothing{.choose_every_frames = 0}}) {
    try {
      CausalTrackSmoother smoother(bad);
      FAIL() << "accepted a window of " << bad.window_frames << " and degree " << bad.degree;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("causal smoothing"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("out of range"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace tactile::capture
