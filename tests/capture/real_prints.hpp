#pragma once
// The vendored real prints (tests/data/polyu-hrf-pores) and the warps the tests put them through.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/capture/print_warp.hpp"

namespace tactile::capture::test {

// image_NN.jpg (kind "image_") or pores_NN.txt (kind "pores_") of print NN.
inline std::filesystem::path print_path(const std::string& nn, const std::string& kind) {
  return std::filesystem::path(TACTILE_TEST_DATA_DIR) / "polyu-hrf-pores" /
         (kind + nn + (kind == "image_" ? ".jpg" : ".txt"));
}

// The hand-marked pores of print NN (pores_NN.txt), checked against its image's size.
inline std::vector<std::array<double, 2>> marks_of(const std::string& nn, const GrayImage& print) {
  return read_pore_marks(print_path(nn, "pores_"), print.width_px, print.height_px);
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
