#pragma once
// The vendored real prints (tests/data/polyu-hrf-pores) and the warps the tests put them through.

#include <filesystem>
#include <string>

#include "tactile/capture/image.hpp"
#include "tactile/capture/print_warp.hpp"

namespace tactile::capture::test {

// image_NN.jpg (kind "image_") or pores_NN.txt (kind "pores_") of print NN.
inline std::filesystem::path print_path(const std::string& nn, const std::string& kind) {
  return std::filesystem::path(TACTILE_TEST_DATA_DIR) / "polyu-hrf-pores" /
         (kind + nn + (kind == "image_" ? ".jpg" : ".txt"));
}

// 30 frames of `pattern` at `strain` over the whole print, other settings the defaults (slide,
// rotation, blur, noise, drift).
inline PrintWarpSpec spec_for(const GrayImage& print, WarpPattern pattern, double strain) {
  PrintWarpSpec s;
  s.width_px = print.width_px;
  s.height_px = print.height_px;
  s.pattern = pattern;
  s.strain = strain;
  s.frame_count = 30;
  return s;
}

}  // namespace tactile::capture::test
