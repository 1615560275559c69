// The smoothing of a frame's steps across neighbouring tracks: exact on the motions its quadratic
// can follow, quieter than the measured steps on noise, and its reach chosen by the steps: long
// where the motion is smooth, short where it changes within a millimetre.

#include "tactile/capture/neighbour_smoothing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>

namespace tactile::capture {
namespace {

constexpr double kPxPerMm = 47;

using Field = std::function<std::array<double, 2>(double x_px, double y_px)>;

// Steps of tracks on a jittered grid `spacing_px` apart over a 320 x 240 view, each moved by
// `field` plus Gaussian noise of `noise_px` on its second position.
std::vector<Track> steps_of(const Field& field, double spacing_px, double noise_px, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.3 * spacing_px, 0.3 * spacing_px);
  std::normal_distribution<double> noise(0, noise_px);
  std::vector<Track> steps;
  std::int32_t id = 0;
  for (double y = spacing_px / 2; y < 240; y += spacing_px) {
    for (double x = spacing_px / 2; x < 320; x += spacing_px) {
      Track t;
      t.id = id++;
      const double x0 = x + jitter(rng), y0 = y + jitter(rng);
      const auto d = field(x0, y0);
      t.x_px = {x0, x0 + d[0] + (noise_px > 0 ? noise(rng) : 0)};
      t.y_px = {y0, y0 + d[1] + (noise_px > 0 ? noise(rng) : 0)};
      steps.push_back(t);
    }
  }
  return steps;
}

// RMS distance of the steps' second positions from where `field` moves their first.
double rms_error(const std::vector<Track>& steps, const Field& field) {
  double sum = 0;
  for (const auto& s : steps) {
    const auto d = field(s.x_px[0], s.y_px[0]);
    sum += std::pow(s.x_px[1] - s.x_px[0] - d[0], 2) + std::pow(s.y_px[1] - s.y_px[0] - d[1], 2);
  }
  return std::sqrt(sum / static_cast<double>(steps.size()));
}

const Field quadratic = [](double x, double y) -> std::array<double, 2> {
  return {3 + 0.02 * x - 0.01 * y + 4e-5 * x * x, -1 + 0.005 * y + 3e-5 * x * y - 2e-5 * y * y};
};

TEST(NeighbourSmoothing, AQuadraticMotionIsKeptExactly) {
  auto steps = steps_of(quadratic, 15, 0, 1);
  const auto before = steps;
  smooth_steps_across_neighbours(steps, kPxPerMm, 0.4, 12);
  ASSERT_EQ(steps.size(), before.size());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(steps[i].x_px[0], before[i].x_px[0]);  // the first position stays
    EXPECT_NEAR(steps[i].x_px[1], before[i].x_px[1], 1e-9) << "track " << steps[i].id;
    EXPECT_NEAR(steps[i].y_px[1], before[i].y_px[1], 1e-9) << "track " << steps[i].id;
  }
}

TEST(NeighbourSmoothing, IndependentNoiseIsAveraged) {
  const auto steps = steps_of(quadratic, 15, 0.05, 2);
  auto smoothed = steps;
  smooth_steps_across_neighbours(smoothed, kPxPerMm, 0.5, 12);
  const double before = rms_error(steps, quadratic), after = rms_error(smoothed, quadratic);
  std::printf("noise 0.05 px a coordinate: RMS %.4f px measured, %.4f smoothed\n", before, after);
  // Within 2.5 sigma (1.25 mm) of a track lie about 30 others 15 px (0.32 mm) apart: a
  // quadratic's six terms fitted to them leave well under half the noise at the centre.
  EXPECT_LT(after, 0.5 * before);
}

TEST(NeighbourSmoothing, ATrackWithTooFewNeighboursKeepsItsOwnStep) {
  // 100 px apart: no other track within 2.5 x 0.4 mm (47 px).
  auto steps = steps_of(quadratic, 100, 0.05, 3);
  const auto before = steps;
  smooth_steps_across_neighbours(steps, kPxPerMm, 0.4, 12);
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(steps[i].x_px[1], before[i].x_px[1]);
    EXPECT_EQ(steps[i].y_px[1], before[i].y_px[1]);
  }
}

// The choice over `frames` frames of steps of `field` with noise, and its sigma at the end.
double chosen_sigma(const Field& field, int frames) {
  NeighbourStepSmoother smoother({}, kPxPerMm);
  for (int f = 0; f < frames; ++f) {
    auto steps = steps_of(field, 15, 0.05, static_cast<unsigned>(100 + f));
    smoother.smooth(steps);
  }
  EXPECT_GE(smoother.choices(), 1);
  return smoother.sigma_mm();
}

TEST(NeighbourSmoothing, NothingIsSmoothedBeforeTheFirstChoice) {
  NeighbourStepSmoother smoother({}, kPxPerMm);
  auto steps = steps_of(quadratic, 15, 0.05, 4);
  const auto before = steps;
  smoother.smooth(steps);
  EXPECT_EQ(smoother.sigma_mm(), 0);
  EXPECT_EQ(steps[10].x_px[1], before[10].x_px[1]);
}

TEST(NeighbourSmoothing, ASmoothMotionGetsTheLongestReach) {
  // A quadratic has no bias at any reach, and the longest averages the most noise.
  EXPECT_EQ(chosen_sigma(quadratic, 6), kNeighbourSigmaCandidatesMm.back());
}

TEST(NeighbourSmoothing, AMotionThatChangesWithinAMillimetreGetsTheShortestReach) {
  // A 1 px wave of 1.5 mm wavelength along x: a 0.8 mm sigma flattens it by far more than the
  // 0.05 px of noise, the shortest reach (0.3 mm) follows it.
  const Field wave = [](double x, double) -> std::array<double, 2> {
    return {std::sin(2 * std::numbers::pi * x / (1.5 * kPxPerMm)), 0};
  };
  EXPECT_EQ(chosen_sigma(wave, 6), kNeighbourSigmaCandidatesMm.front());
}

TEST(NeighbourSmoothing, AFixedSigmaIsUsedFromTheFirstFrameAndNeverChosen) {
  NeighbourStepSmoother smoother({.sigma_mm = 0.5}, kPxPerMm);
  auto steps = steps_of(quadratic, 15, 0.05, 5);
  auto by_function = steps;
  smoother.smooth(steps);
  smooth_steps_across_neighbours(by_function, kPxPerMm, 0.5, 12);
  EXPECT_EQ(smoother.sigma_mm(), 0.5);
  EXPECT_EQ(smoother.choices(), 0);
  EXPECT_EQ(steps[10].x_px[1], by_function[10].x_px[1]);
}

TEST(NeighbourSmoothing, AStepOfOtherThanTwoPositionsIsRefusedNamingTheTrack) {
  auto steps = steps_of(quadratic, 15, 0, 6);
  steps[3].x_px.push_back(1);
  steps[3].y_px.push_back(1);
  try {
    smooth_steps_across_neighbours(steps, kPxPerMm, 0.4, 12);
    FAIL() << "a track of three positions was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("track 3 has 3 positions"), std::string::npos) << e.what();
  }
}

TEST(NeighbourSmoothing, PositionsNoViewCouldHoldAreRefusedNamingThem) {
  auto steps = steps_of(quadratic, 15, 0, 7);
  steps[5].x_px[0] = std::numeric_limits<double>::quiet_NaN();
  try {
    smooth_steps_across_neighbours(steps, kPxPerMm, 0.4, 12);
    FAIL() << "a track at no position was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("track 5 is at no finite position"), std::string::npos)
        << e.what();
  }
  // A grid of cells over a span this wide would take gigabytes: refused before it is made.
  for (const double far_px : {1e12, 1e300}) {
    steps = steps_of(quadratic, 15, 0, 7);
    steps[5].x_px[0] = far_px;
    try {
      smooth_steps_across_neighbours(steps, kPxPerMm, 0.4, 12);
      ADD_FAILURE() << "a track " << far_px << " px away was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("far beyond a camera's view"), std::string::npos)
          << e.what();
    }
  }
}

TEST(NeighbourSmoothing, OutOfRangeSettingsAreRefusedNamingThem) {
  for (const auto& [bad, says] : std::vector<std::pair<NeighbourSmoothing, std::string>>{
           {{.sigma_mm = 0.05}, "sigma 0.05 mm"},
           {{.sigma_mm = 6}, "sigma 6 mm"},
           {{.sigma_mm = -2}, "sigma -2 mm"},
           {{.min_neighbours = 5}, "5 neighbours"},
           {{.choose_every_frames = 0}, "every 0 frames"}}) {
    try {
      check_neighbour_smoothing(bad);
      ADD_FAILURE() << "taken: " << says;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace tactile::capture
