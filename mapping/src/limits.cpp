// Clamp and slew-rate limit, the same two limits the firmware enforces.

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tactile/mapping/limits.hpp"

namespace tactile::mapping {

movie::TactileMovie apply_limits(movie::TactileMovie movie, double slew_limit_um_per_s) {
  if (!(slew_limit_um_per_s > 0)) {
    throw std::invalid_argument(
        fmt::format("slew limit {} um/s must be positive", slew_limit_um_per_s));
  }
  if (!(movie.rate_hz > 0)) {
    throw std::invalid_argument(fmt::format("movie rate {} Hz must be positive", movie.rate_hz));
  }
  const auto& layout = movie.layout;
  if (!(layout.deflection_min_um <= layout.deflection_max_um)) {
    throw std::invalid_argument(fmt::format("layout deflection range [{}, {}] um is empty",
                                            layout.deflection_min_um, layout.deflection_max_um));
  }
  const auto n = static_cast<std::size_t>(std::max(layout.contactor_count(), 0));
  const auto frames = static_cast<std::size_t>(std::max(movie.frame_count, 0));
  if (movie.deflection_um.size() != n * frames) {
    throw std::invalid_argument(fmt::format("movie holds {} deflections for {} frames of {}",
                                            movie.deflection_um.size(), frames, n));
  }
  const double lo = layout.deflection_min_um;
  const double hi = layout.deflection_max_um;
  const double step_um = slew_limit_um_per_s / movie.rate_hz;
  std::vector<double> previous(n, std::clamp(0.0, lo, hi));
  for (std::size_t f = 0; f < frames; ++f) {
    for (std::size_t j = 0; j < n; ++j) {
      auto& value = movie.deflection_um[f * n + j];
      // NaN (a method's bug, never a measurement) goes to neutral rather than to the device.
      const double target = std::clamp<double>(std::isnan(value) ? 0.0 : value, lo, hi);
      const double next = std::clamp(target, previous[j] - step_um, previous[j] + step_um);
      previous[j] = next;
      value = static_cast<float>(next);
    }
  }
  return movie;
}

}  // namespace tactile::mapping
