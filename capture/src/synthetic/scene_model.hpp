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
  // Partial slip (flat-rotate, flat-stick-slip): the load at `frame` (twist in radians, or rim
  // displacement along x in mm) and the slipped fraction of it at image position x, 0 inside
  // the stick region, rising smoothly to 1 at the patch edge.
  double partial_slip_load(int frame) const;
  double slip_fraction(PointMm x) const;
  // Whether the image <-> skin map is the static field of the feature scaled by the indentation
  // and shifted by the slide (so the renderer can precompute it), rather than partial slip.
  bool is_sliding_scene() const {
    return kind_ == Scene::flat_slide || kind_ == Scene::bump || kind_ == Scene::hole;
  }
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
  Scene kind_;
  double skin_margin_mm_;  // how far skin may move beyond the field (texture sizing)
};

}  // namespace tactile::capture
