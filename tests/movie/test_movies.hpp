#pragma once
// Synthetic movies with known content for the display tests.

#include <cmath>
#include <numbers>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::movie::testing {

// Every contactor follows a sine of `amplitude_um` at `frequency_hz`, phase shifted along the
// row-major index so that frames and contactors are all distinct.
inline TactileMovie sine_movie(const Layout& layout, double rate_hz, std::int32_t frames,
                               double amplitude_um, double frequency_hz = 5) {
  TactileMovie m;
  m.layout = layout;
  m.rate_hz = rate_hz;
  m.frame_count = frames;
  const auto n = layout.contactor_count();
  m.deflection_um.resize(static_cast<std::size_t>(frames) * static_cast<std::size_t>(n));
  for (std::int32_t f = 0; f < frames; ++f) {
    for (std::int32_t k = 0; k < n; ++k) {
      const double phase = 2 * std::numbers::pi * (frequency_hz * f / rate_hz + 0.37 * k / n);
      m.deflection_um[static_cast<std::size_t>(f) * n + k] =
          static_cast<float>(amplitude_um * std::sin(phase));
    }
  }
  m.provenance.program_version = "test";
  m.provenance.input = "sine";
  m.provenance.command_line = "tactile test --sine";
  m.provenance.method = "none";
  m.provenance.parameters_json = R"({"amplitude_um":1})";
  return m;
}

}  // namespace tactile::movie::testing
