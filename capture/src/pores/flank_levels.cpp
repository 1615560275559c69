#include "pores/flank_levels.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numbers>
#include <stdexcept>

namespace tactile::capture {

namespace {

// Anisotropic Gaussian, long axis at `angle_rad` (image x to the right, y down), unit sum,
// with the middle band |along| < gap_px left out: the level it measures at a pixel comes from
// either side of it along the ridge, so a pore does not lift its own ridge level.
cv::Mat flank_kernel(double angle_rad, double along_px, double across_px, double gap_px) {
  const int half = std::max(1, static_cast<int>(std::ceil(3.0 * along_px)));
  cv::Mat k(2 * half + 1, 2 * half + 1, CV_32F);
  const double c = std::cos(angle_rad);
  const double s = std::sin(angle_rad);
  double sum = 0;
  for (int y = -half; y <= half; ++y) {
    for (int x = -half; x <= half; ++x) {
      const double u = x * c + y * s;
      const double v = -x * s + y * c;
      const double w =
          std::abs(u) < gap_px
              ? 0.0
              : std::exp(-u * u / (2 * along_px * along_px) - v * v / (2 * across_px * across_px));
      k.at<float>(y + half, x + half) = static_cast<float>(w);
      sum += w;
    }
  }
  return k / sum;
}

}  // namespace

void ridge_directions(const float* jxx, const float* jyy, const float* jxy, int count, int n,
                      int* direction) {
  const double step = std::numbers::pi / n;
  const double margin = 1e-4 * n;
  const auto exact = [&](double a, double b, double d) {
    const double ridge = 0.5 * std::atan2(2.0 * d, a - b) + std::numbers::pi / 2;
    return ((static_cast<int>(std::lround(ridge / step)) % n) + n) % n;
  };
  for (int i = 0; i < count; ++i) {
    const double a = jxx[i], b = jyy[i], d = jxy[i];
    const double x = a - b, y = 2.0 * d;
    const double ax = std::abs(x), ay = std::abs(y);
    const double big = std::max(ax, ay);
    const double t = big > 0 ? std::min(ax, ay) / big : 0.0;
    // atan(t) on [0, 1] within 1e-5 rad (Abramowitz and Stegun 4.4.49).
    const double t2 = t * t;
    double angle =
        t * (0.9998660 + t2 * (-0.3302995 + t2 * (0.1801410 + t2 * (-0.0851330 + t2 * 0.0208351))));
    if (ay > ax) angle = std::numbers::pi / 2 - angle;
    if (x < 0) angle = std::numbers::pi - angle;
    if (std::signbit(y)) angle = -angle;
    const double v = (0.5 * angle + std::numbers::pi / 2) / step;
    const double below = std::floor(v);
    // 1e-5 rad is 1.6e-6 n of a step: a value over 60 times that from a half step rounds as
    // the exact angle's does; one nearer (or not finite) takes the exact formula.
    if (!(std::abs(v - below - 0.5) >= margin)) {
      direction[i] = exact(a, b, d);
      continue;
    }
    const int k = static_cast<int>(below) + (v - below > 0.5 ? 1 : 0);
    direction[i] = ((k % n) + n) % n;
  }
}

FlankKernels flank_kernels(int n, double along_px, double across_px, double gap_px) {
  FlankKernels f;
  const double step = std::numbers::pi / n;
  const int rows = 2 * std::max(1, static_cast<int>(std::ceil(3.0 * along_px))) + 1;
  f.half = rows / 2;
  f.stride = (rows + FlankKernels::kLanes - 1) / FlankKernels::kLanes * FlankKernels::kLanes;
  f.taps.assign(static_cast<std::size_t>(n * rows * f.stride), 0.0F);
  for (int k = 0; k < n; ++k) {
    const cv::Mat kernel = flank_kernel(k * step, along_px, across_px, gap_px);
    // Taps under 1e-7 of the sum: together they move a level by far less than the float
    // rounding of the sum itself.
    for (int r = 0; r < rows; ++r) {
      float* row = &f.taps[static_cast<std::size_t>((k * rows + r) * f.stride)];
      int begin = rows, end = 0;
      for (int c = 0; c < rows; ++c) {
        const float w = kernel.at<float>(r, c);
        if (w < 1e-7F) continue;
        row[c] = w;
        begin = std::min(begin, c);
        end = c + 1;
      }
      if (begin >= end) {
        f.spans.emplace_back(0, 0);
        continue;
      }
      begin -= begin % FlankKernels::kLanes;
      end = std::min(
          f.stride, (end + FlankKernels::kLanes - 1) / FlankKernels::kLanes * FlankKernels::kLanes);
      f.spans.emplace_back(begin, end);
    }
  }
  return f;
}

// Four taps at a time.
float flank_level(const FlankKernels& kernels, int k, const cv::Mat& padded, int y, int x) {
  using Lanes = float __attribute__((vector_size(16)));
  const int rows = 2 * kernels.half + 1;
  const float* taps = &kernels.taps[static_cast<std::size_t>(k * rows * kernels.stride)];
  const auto* spans = &kernels.spans[static_cast<std::size_t>(k * rows)];
  Lanes sum = {0, 0, 0, 0};
  for (int r = 0; r < rows; ++r) {
    const float* w = taps + r * kernels.stride;
    const float* v = padded.ptr<float>(y + r) + x;
    for (int c = spans[r].first; c < spans[r].second; c += FlankKernels::kLanes) {
      Lanes wl, vl;
      std::memcpy(&wl, w + c, sizeof wl);
      std::memcpy(&vl, v + c, sizeof vl);
      sum += wl * vl;
    }
  }
  return (sum[0] + sum[1]) + (sum[2] + sum[3]);
}

#if defined(__x86_64__) && defined(__GNUC__)

namespace {

// Neighbouring pixels of one direction at once, as many as Lanes holds: each pixel's taps are
// summed in flank_level's order (four partial sums by tap column modulo four, combined in
// pairs, no fused multiply-add: this file is compiled without contraction), so the levels are
// the same to the bit, at a fraction of the instructions.
template <class Lanes>
__attribute__((always_inline)) inline void levels_at_once(const FlankKernels& kernels, int k,
                                                          const cv::Mat& padded, int y, int x,
                                                          float* out) {
  const int rows = 2 * kernels.half + 1;
  const float* taps = &kernels.taps[static_cast<std::size_t>(k * rows * kernels.stride)];
  const auto* spans = &kernels.spans[static_cast<std::size_t>(k * rows)];
  Lanes sum[FlankKernels::kLanes] = {};
  for (int r = 0; r < rows; ++r) {
    const float* w = taps + r * kernels.stride;
    const float* v = padded.ptr<float>(y + r) + x;
    for (int c = spans[r].first; c < spans[r].second; c += FlankKernels::kLanes) {
      for (int j = 0; j < FlankKernels::kLanes; ++j) {
        Lanes vl;
        std::memcpy(&vl, v + c + j, sizeof vl);
        sum[j] += w[c + j] * vl;
      }
    }
  }
  const Lanes level = (sum[0] + sum[1]) + (sum[2] + sum[3]);
  std::memcpy(out, &level, sizeof level);
}

__attribute__((target("avx"))) void levels_of_eight_avx(const FlankKernels& kernels, int k,
                                                        const cv::Mat& padded, int y, int x,
                                                        float* out) {
  levels_at_once<float __attribute__((vector_size(32)))>(kernels, k, padded, y, x, out);
}

__attribute__((target("avx512f"))) void levels_of_sixteen_avx512(const FlankKernels& kernels, int k,
                                                                 const cv::Mat& padded, int y,
                                                                 int x, float* out) {
  levels_at_once<float __attribute__((vector_size(64)))>(kernels, k, padded, y, x, out);
}

}  // namespace

bool has_flank_levels_of_eight() {
  return __builtin_cpu_supports("avx");
}

bool has_flank_levels_of_sixteen() {
  return __builtin_cpu_supports("avx512f");
}

void flank_levels_of_sixteen(const FlankKernels& kernels, int k, const cv::Mat& padded, int y,
                             int x, float* out) {
  if (!has_flank_levels_of_sixteen()) {
    throw std::logic_error("flank_levels_of_sixteen: no AVX-512 here");
  }
  levels_of_sixteen_avx512(kernels, k, padded, y, x, out);
}

void flank_levels_of_eight(const FlankKernels& kernels, int k, const cv::Mat& padded, int y, int x,
                           float* out) {
  if (!has_flank_levels_of_eight()) throw std::logic_error("flank_levels_of_eight: no AVX here");
  levels_of_eight_avx(kernels, k, padded, y, x, out);
}

#else

bool has_flank_levels_of_eight() {
  return false;
}

void flank_levels_of_eight(const FlankKernels&, int, const cv::Mat&, int, int, float*) {
  throw std::logic_error("flank_levels_of_eight: no vector instructions here");
}

bool has_flank_levels_of_sixteen() {
  return false;
}

void flank_levels_of_sixteen(const FlankKernels&, int, const cv::Mat&, int, int, float*) {
  throw std::logic_error("flank_levels_of_sixteen: no vector instructions here");
}

#endif

}  // namespace tactile::capture
