#pragma once
// The skin's ringing in the simulated sensor's vibration channel (docs/perception-models.md):
// where the skin sliding over the plate meets a change of the surface's slope (an edge, a rim,
// an apex), the change kicks a resonator (the skin and fluid, 150 Hz, Q = 3). The kick is the
// change of slope itself, a pure number, so an edge rings the same at any sliding speed that
// crosses it faster than the ring lasts.

namespace tactile::perception {

class SkinRinging {
 public:
  // rate_hz: the vibration channel's sample rate; gain: counts of kick per unit change of slope.
  SkinRinging(double rate_hz, double gain_per_slope, double resonance_hz = 150.0,
              double quality = 3.0);

  // One sample: whether the skin touches the plate, and the surface's slope (along the
  // direction of sliding) where the skin first meets it. Returns the ringing in counts.
  // Touching down takes the slope as it is, so landing on a feature's side is no edge.
  double step(bool in_contact, double slope);

 private:
  double gain_, a1_, a2_;
  double y1_ = 0, y2_ = 0;
  double slope_ = 0;
  bool in_contact_ = false;
};

}  // namespace tactile::perception
