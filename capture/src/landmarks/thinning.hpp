#pragma once
// Private: binary thinning to a one-pixel skeleton.

#include <opencv2/core.hpp>

namespace tactile::capture {

// Zhang & Suen (1984) parallel thinning of a CV_8U 0/1 image; returns a 0/1 skeleton.
cv::Mat zhang_suen_thinning(const cv::Mat& binary);

// 0 -> 1 transitions round the 8 neighbours of skeleton pixel (x, y), outside the image = 0:
// 1 = valley ending, 2 = valley, 3 or more = fork. Used instead of the paper's plain neighbour
// count: on a thinned staircase a valley pixel can have three neighbours without any fork.
int crossing_number(const cv::Mat& skeleton, int x, int y);

}  // namespace tactile::capture
