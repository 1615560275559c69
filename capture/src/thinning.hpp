#pragma once
// Private: binary thinning to a one-pixel skeleton.

#include <opencv2/core.hpp>

namespace tactile::capture {

// Zhang & Suen (1984) parallel thinning of a CV_8U 0/1 image; returns a 0/1 skeleton.
cv::Mat zhang_suen_thinning(const cv::Mat& binary);

}  // namespace tactile::capture
