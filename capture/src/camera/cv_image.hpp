#pragma once
// Private bridge between the public GrayImage and OpenCV matrices.

#include <opencv2/core.hpp>

#include "tactile/capture/image.hpp"

namespace tactile::capture {

// A CV_8U header over the image's pixels (no copy); valid while `image` lives unchanged.
inline cv::Mat as_mat(const GrayImage& image) {
  return cv::Mat(image.height_px, image.width_px, CV_8U,
                 const_cast<std::uint8_t*>(image.pixels.data()));
}

// Copies a CV_8U matrix into a GrayImage.
inline GrayImage from_mat(const cv::Mat& mat) {
  GrayImage image;
  image.width_px = mat.cols;
  image.height_px = mat.rows;
  image.pixels.resize(static_cast<std::size_t>(mat.cols) * static_cast<std::size_t>(mat.rows));
  cv::Mat dst(mat.rows, mat.cols, CV_8U, image.pixels.data());
  mat.copyTo(dst);
  return image;
}

}  // namespace tactile::capture
