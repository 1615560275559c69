// Linear resampling of camera-rate frames to the display rate.

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tactile/mapping/resample.hpp"

namespace tactile::mapping {

TimedFrames resample_linear(const TimedFrames& camera, double rate_hz) {
  if (!(rate_hz > 0) || !std::isfinite(rate_hz)) {
    throw std::invalid_argument(fmt::format("resample: rate {} Hz must be positive", rate_hz));
  }
  const auto frames = camera.t_s.size();
  if (frames == 0) throw std::invalid_argument("resample: no camera frames");
  if (camera.values_per_frame < 0 ||
      camera.values.size() != frames * static_cast<std::size_t>(camera.values_per_frame)) {
    throw std::invalid_argument(fmt::format("resample: {} values for {} frames of {} values",
                                            camera.values.size(), frames, camera.values_per_frame));
  }
  for (std::size_t k = 0; k < frames; ++k) {
    if (!std::isfinite(camera.t_s[k]) || (k > 0 && !(camera.t_s[k] > camera.t_s[k - 1]))) {
      throw std::invalid_argument(fmt::format(
          "resample: camera frame times must increase (frame {} at {} s, previous {} s)", k,
          camera.t_s[k], k > 0 ? camera.t_s[k - 1] : camera.t_s[k]));
    }
  }
  const double t0 = camera.t_s.front();
  const double span_s = camera.t_s.back() - t0;
  // The small epsilon keeps a span that is an exact multiple of the period (in decimal) from
  // losing its last frame to rounding.
  const auto count = static_cast<std::size_t>(std::floor(span_s * rate_hz + 1e-9)) + 1;
  const auto n = static_cast<std::size_t>(camera.values_per_frame);

  TimedFrames out;
  out.values_per_frame = camera.values_per_frame;
  out.t_s.resize(count);
  out.values.resize(count * n);
  std::size_t k = 0;  // camera interval [k, k + 1] holding t
  for (std::size_t i = 0; i < count; ++i) {
    const double t = t0 + static_cast<double>(i) / rate_hz;
    out.t_s[i] = t;
    while (k + 2 < frames && camera.t_s[k + 1] <= t) ++k;
    const double* a = camera.values.data() + k * n;
    if (frames == 1) {
      std::copy(a, a + n, out.values.begin() + static_cast<std::ptrdiff_t>(i * n));
      continue;
    }
    const double* b = a + n;
    const double w =
        std::clamp((t - camera.t_s[k]) / (camera.t_s[k + 1] - camera.t_s[k]), 0.0, 1.0);
    for (std::size_t j = 0; j < n; ++j) out.values[i * n + j] = (1.0 - w) * a[j] + w * b[j];
  }
  return out;
}

}  // namespace tactile::mapping
