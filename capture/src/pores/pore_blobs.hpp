#pragma once
// Pores as bright spots above their own ridge level, scored by the pore model
// (PoreDetector::ridge_blob).

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "tactile/capture/features.hpp"

namespace tactile::capture {

// Measures the pore model reads off one candidate (pore_blobs.cpp lists them).
constexpr std::size_t kPoreMeasures = 16;

struct PoreCandidate {
  double x_px = 0;
  double y_px = 0;
  std::array<double, kPoreMeasures> measures{};
};

// Every local maximum of the brightness above the ridge level that lies in `allowed` and at
// least params.min_ridge_depth into a ridge. `gray`: CV_32F image; `allowed`: CV_8U, non-zero
// where features may be reported.
std::vector<PoreCandidate> find_pore_candidates(const cv::Mat& gray, const cv::Mat& allowed,
                                                double px_per_mm, const RidgeBlobParams& params);

// The candidates the pore model keeps, at most one per suppression disc (the likeliest).
std::vector<Feature> find_ridge_blob_pores(const cv::Mat& gray, const cv::Mat& allowed,
                                           double px_per_mm, const RidgeBlobParams& params);

}  // namespace tactile::capture
