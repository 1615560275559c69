#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "tactile/capture/track.hpp"

namespace tactile::capture {
namespace {

// One pore moving at a constant 1.5 px per frame for 60 frames (60 px/mm, so 0.025 mm/frame).
std::vector<std::vector<Feature>> one_moving_pore(int frames) {
  std::vector<std::vector<Feature>> out(static_cast<std::size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    out[static_cast<std::size_t>(f)].push_back({FeatureType::pore, 100 + 1.5 * f, 200, 0});
  }
  return out;
}

TEST(Track, SteadyMotionGivesOneTrackOnTheTruePath) {
  TrackParams p;
  p.min_track_frames = 10;
  const auto tracks = track_features(one_moving_pore(60), uniform_calibration(60, 640, 480), p);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0].first_frame, 0);
  ASSERT_EQ(tracks[0].x_px.size(), 60u);
  // The quadratic smoother is exact on uniform motion.
  for (std::size_t k = 0; k < 60; ++k) EXPECT_NEAR(tracks[0].x_px[k], 100 + 1.5 * k, 1e-9);
}

// The smoother is a local least-squares quadratic, so constant acceleration passes through it
// unchanged, inside the track and at both ends; and a pore among many is matched to itself.
TEST(Track, ConstantAccelerationIsKeptExactlyAmongNeighbours) {
  std::vector<std::vector<Feature>> feats(50);
  for (int f = 0; f < 50; ++f) {
    for (int i = 0; i < 5; ++i) {
      for (int j = 0; j < 5; ++j) {
        feats[static_cast<std::size_t>(f)].push_back(
            {FeatureType::pore, 100 + 30.0 * i + 0.5 * f + 0.01 * f * f, 100 + 30.0 * j, 0});
      }
    }
  }
  TrackParams p;
  p.min_track_frames = 10;
  const auto tracks = track_features(feats, uniform_calibration(60, 640, 480), p);
  ASSERT_EQ(tracks.size(), 25u);
  for (const auto& t : tracks) {
    ASSERT_EQ(t.x_px.size(), 50u);
    const double x0 = t.x_px[0];
    for (std::size_t k = 0; k < 50; ++k) {
      const double f = static_cast<double>(k);
      EXPECT_NEAR(t.x_px[k], x0 + 0.5 * f + 0.01 * f * f, 1e-9);
    }
  }
}

// At frame 40 the pore is lost and a neighbour 6 px (0.1 mm, inside the 0.3 mm search radius)
// to the side is taken for it: the track must be cut there rather than bend towards it.
TEST(Track, AJumpToANeighbourCutsTheTrack) {
  auto feats = one_moving_pore(60);
  for (int f = 40; f < 60; ++f) {
    feats[static_cast<std::size_t>(f)][0].y_px += 6;
  }
  TrackParams p;
  p.min_track_frames = 10;
  const auto tracks = track_features(feats, uniform_calibration(60, 640, 480), p);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_EQ(tracks[0].first_frame, 0);
  EXPECT_EQ(tracks[0].last_frame(), 39);
  EXPECT_EQ(tracks[1].first_frame, 40);
  for (double y : tracks[0].y_px) EXPECT_NEAR(y, 200, 1e-9);
  for (double y : tracks[1].y_px) EXPECT_NEAR(y, 206, 1e-9);
}

TEST(Track, BadParametersAreRejected) {
  TrackParams p;
  p.max_jump_mm = 0;
  EXPECT_THROW(track_features({}, uniform_calibration(60, 640, 480), p), std::invalid_argument);
  Calibration no_scale;
  no_scale.mm_per_px = 0;
  EXPECT_THROW(track_features({}, no_scale, TrackParams{}), std::invalid_argument);
}

// A 20 x 15 grid of tracks 14 px apart over 30 frames, all sliding 1 px a frame, with white
// position noise of noise_px; a strain wave of `strain` along x with a wavelength of 141 px
// travels past them with a period of period_frames (0: no wave).
std::vector<Track> grid_tracks(double noise_px, double strain, double period_frames) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, noise_px);
  const double k = 2 * std::numbers::pi / 141.0;
  std::vector<Track> tracks;
  for (int r = 0; r < 15; ++r) {
    for (int c = 0; c < 20; ++c) {
      Track t;
      t.id = static_cast<std::int32_t>(tracks.size());
      const double x0 = 20 + 14.0 * c, y0 = 20 + 14.0 * r;
      for (int f = 0; f < 30; ++f) {
        const double phase = period_frames > 0 ? 2 * std::numbers::pi * f / period_frames : 0;
        const double wave = strain / k * std::sin(k * x0 - phase);
        t.x_px.push_back(x0 + f + wave + noise(rng));
        t.y_px.push_back(y0 + noise(rng));
      }
      tracks.push_back(std::move(t));
    }
  }
  return tracks;
}

TEST(Track, SmoothingIsAsLongAsTheNoiseAllowsAndNoLongerThanTheStrainAllows) {
  constexpr double kMaxResidualPx = 0.06;
  // White noise alone: a long window (over 30 frames the longest ones differ little, as most
  // of their fits are cut by the track's ends).
  EXPECT_GE(smoothing_that_fits(grid_tracks(0.01, 0, 0), 12, kMaxResidualPx), 8);
  // ... and never longer than asked.
  EXPECT_EQ(smoothing_that_fits(grid_tracks(0.01, 0, 0), 6, kMaxResidualPx), 6);
  // A 2 % wave changing over 5 frames (0.28 px between neighbours against 0.01 px of noise)
  // is bent by every window: no smoothing.
  EXPECT_EQ(smoothing_that_fits(grid_tracks(0.01, 0.02, 5), 12, kMaxResidualPx), 0);
  // Over a 30-frame period a 25-frame window flattens the wave, a few frames' window does not.
  const int slow = smoothing_that_fits(grid_tracks(0.01, 0.02, 30), 12, kMaxResidualPx);
  EXPECT_GE(slow, 3);
  EXPECT_LT(slow, 12);
  // More noise on the same motion (with what smoothing removes still under the 0.06 px bound on
  // how far it may move a track): at least as long a window.
  EXPECT_GE(smoothing_that_fits(grid_tracks(0.02, 0.02, 30), 12, kMaxResidualPx), slow);
  // Noise beyond that bound: no window may move the tracks so far.
  EXPECT_EQ(smoothing_that_fits(grid_tracks(0.2, 0, 0), 12, kMaxResidualPx), 0);
  EXPECT_EQ(smoothing_that_fits(grid_tracks(0.01, 0, 0), 0, kMaxResidualPx), 0);
}

// Noise taken as larger than the tracks show it (as where their errors change slowly from frame
// to frame) chooses a longer window on the same tracks; a scale that is no scale is refused.
TEST(Track, ALargerNoiseScaleChoosesALongerSmoothing) {
  constexpr double kMaxResidualPx = 0.06;
  const std::vector<Track> tracks = grid_tracks(0.01, 0.02, 30);
  const int as_seen = smoothing_that_fits(tracks, 12, kMaxResidualPx);
  const int scaled =
      smoothing_that_fits(tracks, 12, kMaxResidualPx, SmoothingKernel::uniform, 1, 4.0);
  EXPECT_GT(scaled, as_seen);
  EXPECT_LE(scaled, 12);
  for (const double bad : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN()}) {
    EXPECT_THROW(smoothing_that_fits(tracks, 12, kMaxResidualPx, SmoothingKernel::uniform, 1, bad),
                 std::invalid_argument);
  }
}

// A local quadratic fit reproduces a quadratic whatever its weights, inside the track and where
// the track cuts the window.
TEST(Track, BothSmoothingKernelsKeepAConstantAcceleration) {
  for (const SmoothingKernel kernel : {SmoothingKernel::uniform, SmoothingKernel::epanechnikov}) {
    Track t;
    for (int f = 0; f < 30; ++f) {
      t.x_px.push_back(5 + 0.8 * f + 0.01 * f * f);
      t.y_px.push_back(9 - 0.3 * f);
    }
    std::vector<Track> tracks{t};
    smooth_tracks(tracks, 8, kernel);
    for (int f = 0; f < 30; ++f) {
      EXPECT_NEAR(tracks[0].x_px[static_cast<std::size_t>(f)], t.x_px[static_cast<std::size_t>(f)],
                  1e-9);
      EXPECT_NEAR(tracks[0].y_px[static_cast<std::size_t>(f)], t.y_px[static_cast<std::size_t>(f)],
                  1e-9);
    }
  }
}

// Frame-to-frame changes between neighbouring tracks (what strain is made of) against the
// noise-free motion, RMS over the grid's horizontal neighbours.
double change_error(const std::vector<Track>& smoothed, const std::vector<Track>& truth) {
  double sum = 0;
  int count = 0;
  for (std::size_t i = 0; i + 1 < smoothed.size(); ++i) {
    if ((i + 1) % 20 == 0) continue;  // the next track starts the next row
    for (std::size_t f = 0; f + 1 < smoothed[i].x_px.size(); ++f) {
      auto change = [&](const std::vector<Track>& v) {
        return (v[i + 1].x_px[f + 1] - v[i].x_px[f + 1]) - (v[i + 1].x_px[f] - v[i].x_px[f]);
      };
      sum += std::pow(change(smoothed) - change(truth), 2);
      ++count;
    }
  }
  return std::sqrt(sum / count);
}

// The slow wave of the test above, at the window each kernel's own estimate chooses: the
// falling weights leave less error in the changes than equal ones.
TEST(Track, FallingWeightsFollowASlowWaveWithLessError) {
  const auto truth = grid_tracks(0.0, 0.02, 30);
  const auto noisy = grid_tracks(0.01, 0.02, 30);
  double error[2];
  int k = 0;
  for (const SmoothingKernel kernel : {SmoothingKernel::uniform, SmoothingKernel::epanechnikov}) {
    auto smoothed = noisy;
    const int h = smoothing_that_fits(noisy, 16, 0.06, kernel);
    EXPECT_GT(h, 0);
    smooth_tracks(smoothed, h, kernel);
    error[k++] = change_error(smoothed, truth);
  }
  EXPECT_LT(error[1], 0.95 * error[0]);
  // Both well below the unsmoothed changes' noise (two positions of 0.01 px on each track).
  EXPECT_LT(error[0], 0.02);
}

}  // namespace
}  // namespace tactile::capture
