// Method "profile": deflection against the slope of a surface under the moving finger.

#include "tactile/mapping/profile.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "tactile/mapping/placement.hpp"

namespace tactile::mapping {
namespace {

double amplitude_mm(const SurfaceProfile& p) {
  switch (p.shape) {
    case ProfileShape::bump:
      return p.height_mm;
    case ProfileShape::hole:
      return -p.height_mm;
    case ProfileShape::flat:
      return 0;
  }
  throw std::invalid_argument("profile: shape out of range");
}

double sigma_mm(const SurfaceProfile& p) {
  if (!(p.width_mm > 0) || !std::isfinite(p.width_mm)) {
    throw std::invalid_argument(fmt::format("profile: width {} mm must be positive", p.width_mm));
  }
  return p.width_mm / (2 * std::sqrt(2 * std::log(2.0)));
}

}  // namespace

std::string to_string(ProfileShape shape) {
  return name_in(kProfileShapeNames, shape);
}

ProfileShape parse_profile_shape(std::string_view name) {
  return parse_name("profile shape", name, kProfileShapeNames);
}

SurfaceProfile profile_of_scene(const capture::SceneSpec& spec) {
  capture::validate_scene(spec);
  SurfaceProfile p;
  // Every scene but the bump and the hole is on flat glass.
  p.shape = spec.scene == capture::Scene::bump   ? ProfileShape::bump
            : spec.scene == capture::Scene::hole ? ProfileShape::hole
                                                 : ProfileShape::flat;
  p.height_mm = spec.feature_height_mm;
  p.width_mm = spec.feature_width_mm;
  const auto cal = capture::true_calibration(spec);
  const auto centre = capture::to_mm(cal, (spec.width_px - 1) / 2.0, (spec.height_px - 1) / 2.0);
  p.feature_x_mm = centre.x_mm;
  p.feature_y_mm = centre.y_mm;
  const double travel_mm = spec.speed_mm_per_s * (spec.frame_count - 1) / spec.frame_rate_hz;
  p.finger_x0_mm = centre.x_mm - travel_mm / 2;
  p.finger_y0_mm = centre.y_mm;
  p.velocity_x_mm_per_s = spec.speed_mm_per_s;
  p.velocity_y_mm_per_s = 0;
  return p;
}

double profile_height_mm(const SurfaceProfile& p, double x_mm, double y_mm) {
  const double s = sigma_mm(p);
  const double dx = x_mm - p.feature_x_mm, dy = y_mm - p.feature_y_mm;
  return amplitude_mm(p) * std::exp(-(dx * dx + dy * dy) / (2 * s * s));
}

capture::PointMm profile_gradient(const SurfaceProfile& p, double x_mm, double y_mm) {
  const double s = sigma_mm(p);
  const double h = profile_height_mm(p, x_mm, y_mm);
  return {-h * (x_mm - p.feature_x_mm) / (s * s), -h * (y_mm - p.feature_y_mm) / (s * s)};
}

std::vector<double> profile_frame(const SurfaceProfile& profile, const movie::Layout& layout,
                                  double t_s, double gain_um_per_slope) {
  Placement finger;
  finger.centre_x_mm = profile.finger_x0_mm + profile.velocity_x_mm_per_s * t_s;
  finger.centre_y_mm = profile.finger_y0_mm + profile.velocity_y_mm_per_s * t_s;
  const auto positions = contactor_positions_mm(layout, finger);
  const bool along_x = layout.axis == movie::DeflectionAxis::x;
  std::vector<double> deflection_um(positions.size());
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const auto g = profile_gradient(profile, positions[i].x_mm, positions[i].y_mm);
    deflection_um[i] = -gain_um_per_slope * (along_x ? g.x_mm : g.y_mm);
  }
  return deflection_um;
}

}  // namespace tactile::mapping
