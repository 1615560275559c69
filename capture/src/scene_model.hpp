#pragma once
// Private: the skin kinematics and contact of a synthetic scene, shared by the renderer and the
// ground-truth functions so that both use exactly the same model.

#include "tactile/capture/synth.hpp"

namespace tactile::capture {

class SceneModel {
 public:
  explicit SceneModel(const SceneSpec& spec);

  double mm_per_px_x() const { return mm_per_px_x_; }
  double mm_per_px_y() const { return mm_per_px_y_; }
  double time_s(int frame) const { return frame / frame_rate_hz_; }

  // Rigid slide of the skin at `frame` (finger displacement since frame 0).
  PointMm slide(int frame) const;
  // How deeply the feature indents the finger at `frame`, 0..1: the contact-pressure profile of
  // the fingertip patch at the feature's position (Hertz-like sqrt(1 - rho^2)).
  double indentation(int frame) const;
  // Lateral skin displacement at image position x caused by the feature, per unit indentation.
  PointMm unit_displacement(PointMm x) const;
  // Loss-of-contact strength per unit indentation at image position x, 0..1.
  double unit_gap(PointMm x) const;
  // Contact 0..1 at image position x in `frame` (patch edge and loss of contact).
  double contact(PointMm x, int frame) const;

  PointMm to_skin(PointMm image, int frame) const;
  PointMm to_image(PointMm skin, int frame) const;

  // Skin-coordinate bounds that any frame can show (for sizing the texture).
  double skin_min_x_mm() const;
  double skin_max_x_mm() const;
  double skin_min_y_mm() const;
  double skin_max_y_mm() const;

 private:
  SceneSpec spec_;
  double mm_per_px_x_;
  double mm_per_px_y_;
  double frame_rate_hz_;
  PointMm feature_centre_;
  PointMm finger_centre0_;
  double sigma_mm_;
  double amplitude_mm_;  // signed: + pushes skin outward (bump), - inward (hole)
  int feature_kind_;     // 0 flat, 1 bump, 2 hole
};

}  // namespace tactile::capture
