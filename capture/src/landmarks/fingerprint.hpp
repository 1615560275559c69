#pragma once
// Private: a fingerprint as seen through an FTIR prism, rendered once in skin (material)
// coordinates, with the exact skin positions of its pores and minutiae.

#include <opencv2/core.hpp>

#include <random>
#include <vector>

#include "tactile/capture/synth.hpp"

namespace tactile::capture {

struct SkinLandmark {
  std::int32_t id = 0;
  FeatureType type = FeatureType::pore;
  PointMm skin;
  double diameter_mm = 0;
};

struct FingerprintTexture {
  cv::Mat reflectance;     // CV_32F, 0 (ridge in contact, dark) .. 1 (bright)
  double origin_x_mm = 0;  // skin position of texel (0, 0)
  double origin_y_mm = 0;
  double texels_per_mm = 1;
  std::vector<SkinLandmark> landmarks;
};

// Renders the skin rectangle [min_x, max_x] x [min_y, max_y] (mm).
FingerprintTexture render_fingerprint(const SceneSpec& spec, double min_x_mm, double max_x_mm,
                                      double min_y_mm, double max_y_mm, double texels_per_mm,
                                      std::mt19937_64& rng);

}  // namespace tactile::capture
