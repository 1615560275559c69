#pragma once
// Camera calibration from an image of a square dot grid (dark dots on a bright field).

#include "tactile/capture/image.hpp"
#include "tactile/capture/strain_movie.hpp"

namespace tactile::capture {

// Finds the dots, indexes them on the grid and fits the px -> mm homography (perspective from
// the prism included). The millimetre origin is put at pixel (0, 0) and the mm x axis along the
// grid direction closest to the image x axis. Throws tactile::FormatError if no grid of at least
// 4 x 4 dots is found.
Calibration calibrate_dot_grid(const GrayImage& image, double spacing_mm = 0.5);

}  // namespace tactile::capture
