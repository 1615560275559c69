// Built-in contactor layouts of the STReSS family and movie validation.
//
// Sources (deflection ranges and rates as published; where a paper gives no figure the value is
// an assumption, marked as such, to be replaced when the lab measures its own device):
//   STReSS  (Pasquero & Hayward 2003): 10 x 10 piezo bimorphs, 1 mm x 1 mm pitch, 700 Hz,
//           lateral deflection +-50 um. Contactor tips ~0.5 mm square (assumption).
//   STReSS2 (Wang & Hayward 2010): 8 x 8 contactors at 1.2 mm x 1.4 mm; deflection +-100 um
//           ("0.1 mm"); 1 kHz refresh (assumption). Contactor 0.5 x 1.0 mm (assumption).
//   Latero  (Levesque et al. 2007, Tactile Labs): 8 x 8 at 1.2 mm x 1.6125 mm, contactors
//           0.5 x 1.4 mm; 750 Hz, the rate OpenLatero's demos run their loop at (the device
//           has no FIFO and moves when a packet arrives); deflection +-100 um (assumption).
//           Blade bytes: LateroBladeMapping (latero_protocol.hpp).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::movie {

// Each in Layout's member order: name, rows, cols, pitch x and y, contactor width and height,
// axis, deflection range, maximum rate.

Layout stress_layout() {
  return {"stress", 10, 10, 1.0, 1.0, 0.5, 0.5, DeflectionAxis::x, -50, 50, 700};
}

Layout stress2_layout() {
  return {"stress2", 8, 8, 1.2, 1.4, 0.5, 1.0, DeflectionAxis::x, -100, 100, 1000};
}

Layout latero_layout() {
  return {"latero", 8, 8, 1.2, 1.6125, 0.5, 1.4, DeflectionAxis::x, -100, 100, 750};
}

Layout layout_by_name(const std::string& name) {
  if (name == "stress") return stress_layout();
  if (name == "stress2") return stress2_layout();
  if (name == "latero") return latero_layout();
  throw std::invalid_argument(
      fmt::format("unknown layout '{}' (known: {})", name, fmt::join(kBuiltinLayoutNames, ", ")));
}

namespace {

bool positive(double v) {
  return std::isfinite(v) && v > 0;
}

void validate_layout(const Layout& l) {
  if (l.rows <= 0 || l.cols <= 0) {
    throw std::invalid_argument("layout '" + l.name + "' has " + std::to_string(l.rows) + " x " +
                                std::to_string(l.cols) + " contactors; both must be positive");
  }
  if (!positive(l.pitch_x_mm) || !positive(l.pitch_y_mm)) {
    throw std::invalid_argument("layout '" + l.name + "' pitch must be positive and finite");
  }
  if (!positive(l.contactor_width_mm) || !positive(l.contactor_height_mm)) {
    throw std::invalid_argument("layout '" + l.name + "' contactor size must be positive");
  }
  if (!std::isfinite(l.deflection_min_um) || !std::isfinite(l.deflection_max_um) ||
      l.deflection_min_um >= l.deflection_max_um) {
    throw std::invalid_argument(
        "layout '" + l.name + "' deflection range [" + std::to_string(l.deflection_min_um) + ", " +
        std::to_string(l.deflection_max_um) + "] um is empty or not finite");
  }
  if (!positive(l.max_rate_hz)) {
    throw std::invalid_argument("layout '" + l.name + "' max_rate_hz must be positive");
  }
}

}  // namespace

void validate_movie(const TactileMovie& movie) {
  validate_layout(movie.layout);
  if (!positive(movie.rate_hz)) {
    throw std::invalid_argument("movie rate_hz " + std::to_string(movie.rate_hz) +
                                " must be positive and finite");
  }
  if (movie.frame_count < 0) {
    throw std::invalid_argument("movie frame_count " + std::to_string(movie.frame_count) +
                                " is negative");
  }
  const auto per_frame = static_cast<std::size_t>(movie.layout.contactor_count());
  const auto expected = per_frame * static_cast<std::size_t>(movie.frame_count);
  if (movie.deflection_um.size() != expected) {
    throw std::invalid_argument("movie has " + std::to_string(movie.deflection_um.size()) +
                                " deflection values, but " + std::to_string(movie.frame_count) +
                                " frames x " + std::to_string(per_frame) + " contactors need " +
                                std::to_string(expected));
  }
  for (std::size_t i = 0; i < movie.deflection_um.size(); ++i) {
    if (!std::isfinite(movie.deflection_um[i])) {
      const auto f = i / per_frame;
      const auto k = i % per_frame;
      const auto cols = static_cast<std::size_t>(movie.layout.cols);
      throw std::invalid_argument("movie deflection at frame " + std::to_string(f) + ", row " +
                                  std::to_string(k / cols) + ", col " + std::to_string(k % cols) +
                                  " is not finite (NaN or infinity)");
    }
  }
}

}  // namespace tactile::movie
