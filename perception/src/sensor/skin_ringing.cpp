#include "tactile/perception/skin_ringing.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tactile::perception {

SkinRinging::SkinRinging(double rate_hz, double gain_per_slope, double resonance_hz, double quality)
    : gain_(gain_per_slope) {
  if (!(rate_hz > 2 * resonance_hz) || !(resonance_hz > 0) || !(quality > 0.5))
    throw std::invalid_argument(
        "skin ringing: the resonance must lie below the Nyquist rate "
        "and its quality factor above 0.5");
  // Two-pole resonator: poles at radius exp(-w0 / 2Q) and angle w0.
  const double w0 = 2 * std::numbers::pi * resonance_hz / rate_hz;
  const double radius = std::exp(-w0 / (2 * quality));
  a1_ = 2 * radius * std::cos(w0);
  a2_ = -radius * radius;
}

double SkinRinging::step(bool in_contact, double slope) {
  const double kick = in_contact && in_contact_ ? slope - slope_ : 0.0;
  in_contact_ = in_contact;
  slope_ = slope;
  const double y = a1_ * y1_ + a2_ * y2_ + gain_ * kick;
  y2_ = y1_;
  y1_ = y;
  return y;
}

}  // namespace tactile::perception
