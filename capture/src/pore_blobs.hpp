#pragma once
// Pores as bright spots above their own ridge level, inside the ridges
// (PoreDetector::ridge_blob).

#include <vector>

#include <opencv2/core.hpp>

#include "tactile/capture/features.hpp"

namespace tactile::capture {

// `gray`: CV_32F image; `allowed`: CV_8U, non-zero where features may be reported.
std::vector<Feature> find_ridge_blob_pores(const cv::Mat& gray, const cv::Mat& allowed,
                                           double px_per_mm, const RidgeBlobParams& params);

}  // namespace tactile::capture
