// The ridge-blob detector's flank filter: eight pixels at once against one at a time.

#include "pores/flank_levels.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

namespace tactile::capture {
namespace {

// The detector's sizes at 47 px/mm: 5 px along the ridge, 1.5 across, 1.9 px gap.
FlankKernels detector_kernels() {
  return flank_kernels(12, 5.0, 1.5, 1.9);
}

TEST(FlankLevels, EveryKernelSumsToOneAndLeavesItsCentreOut) {
  const FlankKernels kernels = detector_kernels();
  const int rows = 2 * kernels.half + 1;
  for (int k = 0; k < 12; ++k) {
    const auto first =
        kernels.taps.begin() + static_cast<std::ptrdiff_t>(k * rows * kernels.stride);
    const double sum = std::accumulate(first, first + rows * kernels.stride, 0.0);
    EXPECT_NEAR(sum, 1.0, 1e-5) << "direction " << k;
    // The pixel itself lies in the left-out band.
    EXPECT_EQ(*(first + kernels.half * kernels.stride + kernels.half), 0.0f) << "direction " << k;
  }
}

// Every group of `width` pixels that starts at any column of random rows (so that the last
// reaches the padding's right edge), filtered at once by `at_once`, against one pixel at a time;
// or, where the machine cannot, the refusal.
void expect_groups_equal_one_pixel_levels(int width, bool runs_here,
                                          void (*at_once)(const FlankKernels&, int, const cv::Mat&,
                                                          int, int, float*)) {
  const FlankKernels kernels = detector_kernels();
  const int rows = 2 * kernels.half + 1;
  const int cols = 64, height = 8;
  // The padding ridge_level gives the image: half a kernel around, stride - rows more right.
  cv::Mat padded(height + 2 * kernels.half, cols + 2 * kernels.half + kernels.stride - rows,
                 CV_32F);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> grey(0.f, 255.f);
  for (int y = 0; y < padded.rows; ++y) {
    for (int x = 0; x < padded.cols; ++x) padded.at<float>(y, x) = grey(rng);
  }
  std::vector<float> group(static_cast<std::size_t>(width));
  if (!runs_here) {
    EXPECT_THROW(at_once(kernels, 0, padded, 0, 0, group.data()), std::logic_error);
    return;
  }
  int compared = 0;
  for (int k = 0; k < 12; ++k) {
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x + width <= cols; ++x) {
        at_once(kernels, k, padded, y, x, group.data());
        for (int u = 0; u < width; ++u) {
          ASSERT_EQ(group[static_cast<std::size_t>(u)], flank_level(kernels, k, padded, y, x + u))
              << width << " at once, direction " << k << ", pixel " << x + u << ", row " << y;
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 12 * height * (cols - width + 1) * width);
}

TEST(FlankLevels, EightPixelsAtOnceGiveEachPixelsOwnLevelToTheBit) {
  expect_groups_equal_one_pixel_levels(8, has_flank_levels_of_eight(), flank_levels_of_eight);
}

TEST(FlankLevels, SixteenPixelsAtOnceGiveEachPixelsOwnLevelToTheBit) {
  expect_groups_equal_one_pixel_levels(16, has_flank_levels_of_sixteen(), flank_levels_of_sixteen);
}

// The formula the detector's directions must equal, as the detector first wrote it.
int direction_by_atan2(float jxx, float jyy, float jxy, int n) {
  const double ridge = 0.5 * std::atan2(2.0 * jxy, double(jxx) - jyy) + std::numbers::pi / 2;
  return ((static_cast<int>(std::lround(ridge / (std::numbers::pi / n))) % n) + n) % n;
}

TEST(FlankLevels, RidgeDirectionsAreTheNearestOfTheNByTheExactAngle) {
  // Tensors at every angle, on and next to the boundaries between directions, signed zeros,
  // and random ones, for 12 directions (the detector's) and for 5 and 64.
  std::vector<float> a, b, d;
  const auto add = [&](double jxx, double jyy, double jxy) {
    a.push_back(static_cast<float>(jxx));
    b.push_back(static_cast<float>(jyy));
    d.push_back(static_cast<float>(jxy));
  };
  for (const int n : {5, 12, 64}) {
    for (int k = 0; k <= 4 * n; ++k) {
      // The angle of (jxx - jyy, 2 jxy) at which the direction changes, and a hair either side.
      const double boundary = (k + 0.5) * 2 * std::numbers::pi / n - std::numbers::pi;
      for (const double off : {-1e-6, -1e-9, 0.0, 1e-9, 1e-6, 0.3}) {
        for (const double r : {1.0, 1e3, 1e-3}) {
          add(r * std::cos(boundary + off) + 5.0, 5.0, 0.5 * r * std::sin(boundary + off));
        }
      }
    }
  }
  add(0, 0, 0);
  add(0, 0, -0.0);
  add(1, 1, 0);
  add(1, 1, -0.0);
  add(0, 1, -0.0);
  add(2, 1, 0.5);  // exactly 45 degrees
  add(1, 2, -0.5);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.f, 4e4f);
  for (int i = 0; i < 100000; ++i) add(u(rng), u(rng), u(rng) - 2e4f);
  for (const int n : {5, 12, 64}) {
    std::vector<int> got(a.size());
    ridge_directions(a.data(), b.data(), d.data(), static_cast<int>(a.size()), n, got.data());
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_EQ(got[i], direction_by_atan2(a[i], b[i], d[i], n))
          << n << " directions, tensor " << a[i] << " " << b[i] << " " << d[i];
    }
  }
}

}  // namespace
}  // namespace tactile::capture
