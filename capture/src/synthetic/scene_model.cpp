#include "synthetic/scene_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "synthetic/carried_edge.hpp"

namespace tactile::capture {

namespace {
double smoothstep(double lo, double hi, double v) {
  const double t = std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}
}  // namespace

std::string to_string(Scene scene) {
  return name_in(kSceneNames, scene);
}

Scene parse_scene(std::string_view name) {
  return parse_name("scene", name, kSceneNames);
}

void validate_scene(const SceneSpec& spec) {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("invalid scene: " + what);
  };
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
  if (!(spec.stick_ratio >= 0 && spec.stick_ratio <= 0.9)) fail("stick_ratio must be in 0..0.9");
  if (!(std::abs(spec.rotation_deg) <= 45)) fail("rotation_deg must be within +-45");
  if (!(std::abs(spec.lateral_amplitude_mm) <= 3)) fail("lateral_amplitude_mm must be within +-3");
  // The image -> skin map of the partial-slip scenes is inverted by fixed-point iteration,
  // which needs the slip field's gradient below 1 (smoothstep slope 1.5 over the slip annulus).
  const double a_min = std::min(spec.contact_semi_x_mm, spec.contact_semi_y_mm);
  const double a_max = std::max(spec.contact_semi_x_mm, spec.contact_semi_y_mm);
  const double slope = 1.5 / ((1 - spec.stick_ratio) * a_min);
  if (spec.scene == Scene::flat_rotate &&
      std::abs(spec.rotation_deg) * std::numbers::pi / 180 * a_max * slope > 0.8) {
    fail("rotation_deg too large for the slip annulus (skin would fold)");
  }
  if (spec.scene == Scene::flat_stick_slip && std::abs(spec.lateral_amplitude_mm) * slope > 0.8) {
    fail("lateral_amplitude_mm too large for the slip annulus (skin would fold)");
  }
}

SceneModel::SceneModel(const SceneSpec& spec) : spec_(spec) {
  validate_scene(spec);
  mm_per_px_x_ = spec.field_width_mm / spec.width_px;
  mm_per_px_y_ = spec.field_height_mm / spec.height_px;
  frame_rate_hz_ = spec.frame_rate_hz;
  const double w_mm = (spec.width_px - 1) * mm_per_px_x_;
  const double h_mm = (spec.height_px - 1) * mm_per_px_y_;
  feature_centre_ = {w_mm / 2, h_mm / 2};
  // The finger's path is centred on the feature so the feature crosses the whole patch.
  kind_ = spec.scene;
  const double travel_mm = slide(spec.frame_count - 1).x_mm;
  finger_centre0_ = {w_mm / 2 - travel_mm / 2, h_mm / 2};
  sigma_mm_ = spec.feature_width_mm / (2 * std::sqrt(2 * std::log(2.0)));
  const double a = spec.displacement_per_height * spec.feature_height_mm;
  amplitude_mm_ = kind_ == Scene::bump ? a : kind_ == Scene::hole ? -a : 0.0;
  // Largest skin motion beyond the field: the feature's push, the rim's twist about the centre
  // (at most the half-diagonal), or the rim's lateral slip.
  const double half_diagonal = std::hypot(w_mm, h_mm) / 2;
  skin_margin_mm_ = std::abs(amplitude_mm_);
  if (kind_ == Scene::flat_rotate) {
    skin_margin_mm_ = std::abs(spec.rotation_deg) * std::numbers::pi / 180 * half_diagonal;
  }
  if (kind_ == Scene::flat_stick_slip) skin_margin_mm_ = std::abs(spec.lateral_amplitude_mm);
}

PointMm SceneModel::slide(int frame) const {
  // The partial-slip scenes press the finger in place: no gross slide.
  if (!is_sliding_scene()) return {0, 0};
  return {spec_.speed_mm_per_s * time_s(frame), 0.0};
}

double SceneModel::partial_slip_load(int frame) const {
  const double n = std::max(1, spec_.frame_count - 1);
  if (kind_ == Scene::flat_rotate) {
    // Twist grows from rest to rotation_deg with zero angular speed at both ends.
    return spec_.rotation_deg * std::numbers::pi / 180 *
           (1 - std::cos(std::numbers::pi * frame / n)) / 2;
  }
  if (kind_ == Scene::flat_stick_slip) {
    // One back-and-forth cycle: out along +x, back through rest to -x, back to rest.
    return spec_.lateral_amplitude_mm * std::sin(2 * std::numbers::pi * frame / n);
  }
  return 0.0;
}

double SceneModel::slip_fraction(PointMm x) const {
  const double dx = (x.x_mm - finger_centre0_.x_mm) / spec_.contact_semi_x_mm;
  const double dy = (x.y_mm - finger_centre0_.y_mm) / spec_.contact_semi_y_mm;
  return smoothstep(spec_.stick_ratio, 1.0, std::sqrt(dx * dx + dy * dy));
}

double SceneModel::indentation(int frame) const {
  if (kind_ != Scene::bump && kind_ != Scene::hole) return 0.0;
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
  if (kind_ != Scene::bump && kind_ != Scene::hole) return 0.0;
  const double dx = x.x_mm - feature_centre_.x_mm;
  const double dy = x.y_mm - feature_centre_.y_mm;
  const double r = std::sqrt(dx * dx + dy * dy);
  if (kind_ == Scene::bump) {
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

namespace {
PointMm rotate_about(PointMm p, PointMm centre, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  const double dx = p.x_mm - centre.x_mm, dy = p.y_mm - centre.y_mm;
  return {centre.x_mm + c * dx - s * dy, centre.y_mm + s * dx + c * dy};
}
}  // namespace

PointMm SceneModel::to_skin(PointMm image, int frame) const {
  if (kind_ == Scene::flat_rotate) {
    return rotate_about(image, finger_centre0_, -partial_slip_load(frame) * slip_fraction(image));
  }
  if (kind_ == Scene::flat_stick_slip) {
    return {image.x_mm - partial_slip_load(frame) * slip_fraction(image), image.y_mm};
  }
  const PointMm u = slide(frame);
  const double p = indentation(frame);
  const PointMm d = unit_displacement(image);
  return {image.x_mm - u.x_mm - p * d.x_mm, image.y_mm - u.y_mm - p * d.y_mm};
}

PointMm SceneModel::to_image(PointMm skin, int frame) const {
  // Every scene's map is x = F(X, x) with F a contraction in x (|grad d| <= |A|/sigma < 1 for
  // the feature; the slip field's gradient is bounded in validate_scene()), so fixed-point
  // iteration converges geometrically.
  auto step = [&](PointMm x) -> PointMm {
    if (kind_ == Scene::flat_rotate) {
      return rotate_about(skin, finger_centre0_, partial_slip_load(frame) * slip_fraction(x));
    }
    if (kind_ == Scene::flat_stick_slip) {
      return {skin.x_mm + partial_slip_load(frame) * slip_fraction(x), skin.y_mm};
    }
    const PointMm u = slide(frame);
    const double p = indentation(frame);
    const PointMm d = unit_displacement(x);
    return {skin.x_mm + u.x_mm + p * d.x_mm, skin.y_mm + u.y_mm + p * d.y_mm};
  };
  const PointMm u = slide(frame);
  PointMm x{skin.x_mm + u.x_mm, skin.y_mm + u.y_mm};
  for (int i = 0; i < 200; ++i) {
    const PointMm next = step(x);
    const double change = std::abs(next.x_mm - x.x_mm) + std::abs(next.y_mm - x.y_mm);
    x = next;
    if (change < 1e-13) break;
  }
  return x;
}

double SceneModel::skin_min_x_mm() const {
  const double travel = std::max(0.0, slide(spec_.frame_count - 1).x_mm);
  return -travel - 1.0 - skin_margin_mm_;
}
double SceneModel::skin_max_x_mm() const {
  const double back = std::max(0.0, -slide(spec_.frame_count - 1).x_mm);
  return spec_.width_px * mm_per_px_x_ + back + 1.0 + skin_margin_mm_;
}
double SceneModel::skin_min_y_mm() const {
  return -1.0 - skin_margin_mm_;
}
double SceneModel::skin_max_y_mm() const {
  return spec_.height_px * mm_per_px_y_ + 1.0 + skin_margin_mm_;
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
  const auto [l0, l1] = carried_edge(a_from, b_from, [&](PointMm p) {
    return model.to_image(model.to_skin(p, frame_from), frame_to);
  });
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
