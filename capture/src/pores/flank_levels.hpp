#pragma once
// The ridge-blob detector's flank filter (pore_blobs.cpp): each pixel filtered with the kernel
// of its own ridge direction. Kept apart so that the eight-pixel version can be tested against
// the one-pixel one.

#include <utility>
#include <vector>

#include <opencv2/core.hpp>

namespace tactile::capture {

// The flank kernels, one per quantised ridge direction, as rows of taps. Each row keeps only
// the span of taps that weigh anything (the kernel is a thin band across a square), widened to
// whole groups of four so that a row is summed four taps at a time.
struct FlankKernels {
  static constexpr int kLanes = 4;
  int half = 0;
  int stride = 0;                          // floats per kernel row, a multiple of kLanes
  std::vector<float> taps;                 // kernel k, row r at (k * rows + r) * stride
  std::vector<std::pair<int, int>> spans;  // [begin, end) of each row, multiples of kLanes
};

// The kernels of n directions (k pi / n): Gaussian along the ridge (along_px) and across it
// (across_px), with the band |along| < gap_px left out.
FlankKernels flank_kernels(int n, double along_px, double across_px, double gap_px);

// One pixel's level: the taps of direction k's kernel over `padded` (the image with half
// kernel rows of border, and stride - rows more on the right), from (x, y) as the top-left tap.
float flank_level(const FlankKernels& kernels, int k, const cv::Mat& padded, int y, int x);

// Each pixel's kernel, for count pixels of the structure tensor (jxx, jyy, jxy): the nearest
// of the n directions k pi / n to the ridge, which runs at right angles to the dominant gradient,
// i.e. lround((atan2(2 jxy, jxx - jyy) / 2 + pi / 2) / (pi / n)) mod n. The same directions as
// that formula, whose `atan2` at every pixel of a 640 x 484 frame took about 5 ms of the
// detector's 40 ms of CPU.
void ridge_directions(const float* jxx, const float* jyy, const float* jxy, int count, int n,
                      int* direction);

// Whether flank_levels_of_eight runs here (AVX on x86-64).
bool has_flank_levels_of_eight();

// Pixels x..x+7 of row y, all of direction k, into out[0..7]: the same sums as flank_level to
// the bit. Only where has_flank_levels_of_eight().
void flank_levels_of_eight(const FlankKernels& kernels, int k, const cv::Mat& padded, int y, int x,
                           float* out);

// Whether flank_levels_of_sixteen runs here (AVX-512 on x86-64).
bool has_flank_levels_of_sixteen();

// Pixels x..x+15 of row y the same way, into out[0..15]. Only where
// has_flank_levels_of_sixteen().
void flank_levels_of_sixteen(const FlankKernels& kernels, int k, const cv::Mat& padded, int y,
                             int x, float* out);

}  // namespace tactile::capture
