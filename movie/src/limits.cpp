// The playable-rate rule, one definition for the mapping that writes movies and the player and
// emulated device that play them.

#include "tactile/movie/limits.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace tactile::movie {

bool is_playable_rate(double rate_hz) {
  return std::isfinite(rate_hz) && rate_hz >= 1 && rate_hz <= kMaxPlayableRateHz &&
         std::abs(rate_hz - std::round(rate_hz)) <= 1e-9;
}

void require_playable_rate(double rate_hz, std::string_view what) {
  if (!is_playable_rate(rate_hz)) {
    throw std::invalid_argument(
        fmt::format("{} {} Hz is not playable: devices play {}", what, rate_hz, kPlayableRateRule));
  }
}

}  // namespace tactile::movie
