// The ridge-blob detector's flank filter: eight pixels at once against one at a time.

#include "pores/flank_levels.hpp"

#include <gtest/gtest.h>

#include <numeric>
#include <random>
#include <stdexcept>

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

TEST(FlankLevels, EightPixelsAtOnceGiveEachPixelsOwnLevelToTheBit) {
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
  if (!has_flank_levels_of_eight()) {
    float out[8];
    EXPECT_THROW(flank_levels_of_eight(kernels, 0, padded, 0, 0, out), std::logic_error);
    return;
  }
  int compared = 0;
  for (int k = 0; k < 12; ++k) {
    for (int y = 0; y < height; ++y) {
      for (int x = 0; x + 8 <= cols; x += 8) {
        float eight[8];
        flank_levels_of_eight(kernels, k, padded, y, x, eight);
        for (int u = 0; u < 8; ++u) {
          ASSERT_EQ(eight[u], flank_level(kernels, k, padded, y, x + u))
              << "direction " << k << ", pixel " << x + u << ", row " << y;
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 12 * height * cols);
}

}  // namespace
}  // namespace tactile::capture
