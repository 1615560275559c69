#include "scene_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace tactile::capture {

namespace {
double smoothstep(double lo, double hi, double v) {
  const double t = std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}
}  // namespace

void validate(const SceneSpec& spec) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("invalid scene: " + what);
  };
  if (spec.scene != "bump" && spec.scene != "hole" && spec.scene != "flat-slide") {
    fail(fmt::format("scene '{}' is not one of bump, hole, flat-slide", spec.scene));
  }
  if (spec.frame_count < 1) fail("frame_count must be >= 1");
  if (!(spec.frame_rate_hz > 0)) fail("frame_rate_hz must be > 0");
  if (spec.width_px < 16 || spec.height_px < 16) fail("image must be at least 16x16 px");
  if (spec.width_px > 8192 || spec.height_px > 8192) fail("image larger than 8192 px");
  if (!(spec.field_width_mm > 0) || !(spec.field_height_mm > 0)) fail("field must be > 0 mm");
  if (!(spec.feature_width_mm > 0)) fail("feature_width_mm must be > 0");
  if (spec.feature_height_mm < 0) fail("feature_height_mm must be >= 0");
  if (!(spec.contact_semi_x_mm > 0) || !(spec.contact_semi_y_mm > 0)) {
    fail("contact patch semi-axes must be > 0");
  }
  if (!(spec.ridge_period_mm > 0.1)) fail("ridge_period_mm must be > 0.1");
  if (!(spec.pore_spacing_mm > 0.1)) fail("pore_spacing_mm must be > 0.1");
  if (!(spec.pore_min_diameter_mm > 0) || spec.pore_max_diameter_mm < spec.pore_min_diameter_mm) {
    fail("pore diameters must satisfy 0 < min <= max");
  }
  if (spec.minutiae_per_mm2 < 0) fail("minutiae_per_mm2 must be >= 0");
  if (spec.blur_sigma_px < 0 || spec.noise_sigma < 0) fail("blur and noise must be >= 0");
  if (!(spec.contrast > 0 && spec.contrast <= 1.0)) fail("contrast must be in (0, 1]");
  if (std::abs(spec.speed_mm_per_s) > 100) fail("speed_mm_per_s above 100");
  if (std::abs(spec.displacement_per_height) > 2) fail("displacement_per_height above 2");
}

SceneModel::SceneModel(const SceneSpec& spec) : spec_(spec) {
  validate(spec);
  mm_per_px_x_ = spec.field_width_mm / spec.width_px;
  mm_per_px_y_ = spec.field_height_mm / spec.height_px;
  frame_rate_hz_ = spec.frame_rate_hz;
  const double w_mm = (spec.width_px - 1) * mm_per_px_x_;
  const double h_mm = (spec.height_px - 1) * mm_per_px_y_;
  feature_centre_ = {w_mm / 2, h_mm / 2};
  // The finger's path is centred on the feature so the feature crosses the whole patch.
  const double travel_mm = spec.speed_mm_per_s * (spec.frame_count - 1) / spec.frame_rate_hz;
  finger_centre0_ = {w_mm / 2 - travel_mm / 2, h_mm / 2};
  sigma_mm_ = spec.feature_width_mm / (2 * std::sqrt(2 * std::log(2.0)));
  feature_kind_ = spec.scene == "bump" ? 1 : spec.scene == "hole" ? 2 : 0;
  const double a = spec.displacement_per_height * spec.feature_height_mm;
  amplitude_mm_ = feature_kind_ == 1 ? a : feature_kind_ == 2 ? -a : 0.0;
}

PointMm SceneModel::slide(int frame) const {
  return {spec_.speed_mm_per_s * time_s(frame), 0.0};
}

double SceneModel::indentation(int frame) const {
  if (feature_kind_ == 0) return 0.0;
  const PointMm u = slide(frame);
  const double dx =
      (feature_centre_.x_mm - finger_centre0_.x_mm - u.x_mm) / spec_.contact_semi_x_mm;
  const double dy =
      (feature_centre_.y_mm - finger_centre0_.y_mm - u.y_mm) / spec_.contact_semi_y_mm;
  return std::sqrt(std::max(0.0, 1 - dx * dx - dy * dy));
}

PointMm SceneModel::unit_displacement(PointMm x) const {
  if (amplitude_mm_ == 0.0) return {0, 0};
  const double dx = x.x_mm - feature_centre_.x_mm;
  const double dy = x.y_mm - feature_centre_.y_mm;
  const double r2 = dx * dx + dy * dy;
  const double f = amplitude_mm_ / sigma_mm_ * std::exp(-r2 / (2 * sigma_mm_ * sigma_mm_));
  return {f * dx, f * dy};
}

double SceneModel::unit_gap(PointMm x) const {
  if (feature_kind_ == 0) return 0.0;
  const double dx = x.x_mm - feature_centre_.x_mm;
  const double dy = x.y_mm - feature_centre_.y_mm;
  const double r = std::sqrt(dx * dx + dy * dy);
  if (feature_kind_ == 1) {
    // Skin bridges from the bump's flank to the glass: a ring without contact.
    const double z = (r - 2.0 * sigma_mm_) / (0.45 * sigma_mm_);
    return std::exp(-z * z);
  }
  // Skin does not follow into the hole: no contact over its middle.
  const double z = r / (0.8 * sigma_mm_);
  return std::exp(-z * z);
}

double SceneModel::contact(PointMm x, int frame) const {
  const PointMm u = slide(frame);
  const double dx = (x.x_mm - finger_centre0_.x_mm - u.x_mm) / spec_.contact_semi_x_mm;
  const double dy = (x.y_mm - finger_centre0_.y_mm - u.y_mm) / spec_.contact_semi_y_mm;
  const double rho = std::sqrt(dx * dx + dy * dy);
  const double patch = 1 - smoothstep(0.96, 1.0, rho);
  const double gap = indentation(frame) * unit_gap(x);
  return patch * (1 - smoothstep(0.4, 0.6, gap));
}

PointMm SceneModel::to_skin(PointMm image, int frame) const {
  const PointMm u = slide(frame);
  const double p = indentation(frame);
  const PointMm d = unit_displacement(image);
  return {image.x_mm - u.x_mm - p * d.x_mm, image.y_mm - u.y_mm - p * d.y_mm};
}

PointMm SceneModel::to_image(PointMm skin, int frame) const {
  // x = X + u + p d(x): a contraction because |grad d| <= |A|/sigma < 1, so fixed-point
  // iteration converges geometrically.
  const PointMm u = slide(frame);
  const double p = indentation(frame);
  PointMm x{skin.x_mm + u.x_mm, skin.y_mm + u.y_mm};
  for (int i = 0; i < 100; ++i) {
    const PointMm d = unit_displacement(x);
    const PointMm next{skin.x_mm + u.x_mm + p * d.x_mm, skin.y_mm + u.y_mm + p * d.y_mm};
    const double change = std::abs(next.x_mm - x.x_mm) + std::abs(next.y_mm - x.y_mm);
    x = next;
    if (change < 1e-13) break;
  }
  return x;
}

double SceneModel::skin_min_x_mm() const {
  const double travel = std::max(0.0, slide(spec_.frame_count - 1).x_mm);
  return -travel - 1.0 - std::abs(amplitude_mm_);
}
double SceneModel::skin_max_x_mm() const {
  const double back = std::max(0.0, -slide(spec_.frame_count - 1).x_mm);
  return spec_.width_px * mm_per_px_x_ + back + 1.0 + std::abs(amplitude_mm_);
}
double SceneModel::skin_min_y_mm() const {
  return -1.0 - std::abs(amplitude_mm_);
}
double SceneModel::skin_max_y_mm() const {
  return spec_.height_px * mm_per_px_y_ + 1.0 + std::abs(amplitude_mm_);
}

PointMm skin_to_image(const SceneSpec& spec, PointMm skin, int frame) {
  return SceneModel(spec).to_image(skin, frame);
}

PointMm image_to_skin(const SceneSpec& spec, PointMm image, int frame) {
  return SceneModel(spec).to_skin(image, frame);
}

double true_rel_change(const SceneSpec& spec, PointMm a_from, PointMm b_from, int frame_from,
                       int frame_to) {
  const SceneModel model(spec);
  const PointMm a_to = model.to_image(model.to_skin(a_from, frame_from), frame_to);
  const PointMm b_to = model.to_image(model.to_skin(b_from, frame_from), frame_to);
  const double l0 = std::hypot(b_from.x_mm - a_from.x_mm, b_from.y_mm - a_from.y_mm);
  const double l1 = std::hypot(b_to.x_mm - a_to.x_mm, b_to.y_mm - a_to.y_mm);
  if (l0 <= 0) throw std::invalid_argument("true_rel_change: the two points coincide");
  return (l1 - l0) / l0;
}

bool in_contact(const SceneSpec& spec, PointMm image, int frame) {
  return SceneModel(spec).contact(image, frame) >= 0.5;
}

Calibration true_calibration(const SceneSpec& spec) {
  const SceneModel model(spec);
  Calibration c;
  c.px_to_mm = {model.mm_per_px_x(), 0, 0, 0, model.mm_per_px_y(), 0, 0, 0, 1};
  c.mm_per_px = std::sqrt(model.mm_per_px_x() * model.mm_per_px_y());
  c.image_width_px = spec.width_px;
  c.image_height_px = spec.height_px;
  c.method = "synthetic camera (exact)";
  return c;
}

}  // namespace tactile::capture
