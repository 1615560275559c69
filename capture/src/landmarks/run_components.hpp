#pragma once
// Private: 4-connected components of a binary image, labelled on horizontal runs of set pixels
// (union-find over runs that overlap the row above). Same components and the same raster order
// of first pixels as cv::connectedComponentsWithStats(..., 4), several times faster on prints,
// whose valleys are long runs.

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace tactile::capture {

struct PixelRun {
  std::int32_t y;
  std::int32_t x_begin;  // first set pixel
  std::int32_t x_end;    // one past the last
  std::int32_t component;
};

struct RunComponent {
  std::int64_t area = 0;
  std::int32_t x_min = 0, y_min = 0, x_max = 0, y_max = 0;  // inclusive bounding box
};

struct RunLabels {
  std::vector<PixelRun> runs;            // raster order
  std::vector<RunComponent> components;  // in raster order of their first pixel
};

// binary: CV_8U, nonzero = set.
RunLabels label_runs_4(const cv::Mat& binary);

}  // namespace tactile::capture
