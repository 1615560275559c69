// Mapping parameters: the accepted names, validation before any work, and their JSON record.

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tactile/mapping/map.hpp"
#include "tactile/movie/limits.hpp"

namespace tactile::mapping {
namespace {

void require_positive(double value, const char* what) {
  if (!(value > 0) || !std::isfinite(value)) {
    throw std::invalid_argument(
        fmt::format("mapping: {} must be positive and finite, got {}", what, value));
  }
}

}  // namespace

std::string to_string(MappingMethod method) {
  return name_in(kMappingMethodNames, method);
}
std::string to_string(Normalisation normalisation) {
  return name_in(kNormalisationNames, normalisation);
}
std::string to_string(StrainMode strain) {
  return name_in(kStrainModeNames, strain);
}

MappingMethod parse_mapping_method(std::string_view name) {
  return parse_name("method", name, kMappingMethodNames);
}
Normalisation parse_normalisation(std::string_view name) {
  return parse_name("normalisation", name, kNormalisationNames);
}
StrainMode parse_strain_mode(std::string_view name) {
  return parse_name("strain", name, kStrainModeNames);
}

MappingParams resolve_mapping_params(const MappingParams& requested, const movie::Layout& layout) {
  MappingParams params = requested;
  if (!params.rate_hz) params.rate_hz = layout.max_rate_hz;
  const double rate_hz = *params.rate_hz;
  if (params.method == MappingMethod::profile) {
    if (!params.profile) {
      throw std::invalid_argument(
          "mapping: method 'profile' needs a surface profile (a synthetic or ground-truth scene "
          "in an experiment)");
    }
    profile_height_mm(*params.profile, 0, 0);  // throws on a bad width
    require_positive(params.profile->height_mm + 1.0, "profile height_mm + 1");
  }
  require_positive(params.accumulate.max_edge_ratio, "accumulate max_edge_ratio");
  require_positive(params.gain_um_per_strain, "gain_um_per_strain");
  require_positive(rate_hz, "rate_hz");
  require_positive(params.slew_limit_um_per_s, "slew_limit_um_per_s");
  if (!(params.peak_fraction > 0 && params.peak_fraction <= 1)) {
    throw std::invalid_argument(
        fmt::format("mapping: peak_fraction must be in (0, 1], got {}", params.peak_fraction));
  }
  if (!(params.field.min_triangle_quality >= 0 && params.field.min_triangle_quality < 1)) {
    throw std::invalid_argument(
        fmt::format("mapping: min_triangle_quality must be in [0, 1), got {}",
                    params.field.min_triangle_quality));
  }
  if (params.placement) {
    const auto& p = *params.placement;
    require_positive(p.scale, "placement scale");
    if (!std::isfinite(p.centre_x_mm) || !std::isfinite(p.centre_y_mm) ||
        !std::isfinite(p.rotation_rad)) {
      throw std::invalid_argument("mapping: placement centre and rotation must be finite");
    }
  }
  if (layout.rows <= 0 || layout.cols <= 0) {
    throw std::invalid_argument(fmt::format("mapping: layout '{}' has {} x {} contactors",
                                            layout.name, layout.rows, layout.cols));
  }
  require_positive(layout.pitch_x_mm, "layout pitch_x_mm");
  require_positive(layout.pitch_y_mm, "layout pitch_y_mm");
  if (!(layout.deflection_min_um <= layout.deflection_max_um)) {
    throw std::invalid_argument(
        fmt::format("mapping: layout '{}' deflection range [{}, {}] um is empty", layout.name,
                    layout.deflection_min_um, layout.deflection_max_um));
  }
  if (rate_hz > layout.max_rate_hz) {
    throw std::invalid_argument(
        fmt::format("mapping: rate {} Hz is above layout '{}' maximum rate {} Hz", rate_hz,
                    layout.name, layout.max_rate_hz));
  }
  movie::require_playable_rate(rate_hz, "mapping: rate");
  return params;
}

std::string parameters_json(const MappingParams& params, const Placement& placement_used,
                            double normalisation_factor) {
  nlohmann::json j;
  j["method"] = to_string(params.method);
  j["gain_um_per_strain"] = params.gain_um_per_strain;
  j["normalisation"] = to_string(params.normalisation);
  j["peak_fraction"] = params.peak_fraction;
  j["normalisation_factor"] = normalisation_factor;
  j["rate_hz"] = params.rate_hz.value_or(0.0);  // set once resolved
  j["strain"] = to_string(params.strain);
  if (params.strain == StrainMode::accumulated) {
    j["reference_frame"] = params.accumulate.reference_frame;
    j["max_edge_ratio"] = params.accumulate.max_edge_ratio;
  }
  j["placement"] = {{"centre_x_mm", placement_used.centre_x_mm},
                    {"centre_y_mm", placement_used.centre_y_mm},
                    {"rotation_rad", placement_used.rotation_rad},
                    {"scale", placement_used.scale},
                    {"auto", !params.placement.has_value()}};
  j["slew_limit_um_per_s"] = params.slew_limit_um_per_s;
  if (params.method == MappingMethod::profile && params.profile) {
    const auto& p = *params.profile;
    j["profile"] = {
        {"shape", to_string(p.shape)},
        {"height_mm", p.height_mm},
        {"width_mm", p.width_mm},
        {"feature_mm", {p.feature_x_mm, p.feature_y_mm}},
        {"finger_start_mm", {p.finger_x0_mm, p.finger_y0_mm}},
        {"velocity_mm_per_s", {p.velocity_x_mm_per_s, p.velocity_y_mm_per_s}},
        {"rule", "d = -gain * dh/d(axis) at the contactor, grid riding with the finger"}};
  }
  j["min_triangle_quality"] = params.field.min_triangle_quality;
  j["spatial_interpolation"] = "piecewise constant per triangle";
  j["time_interpolation"] = "linear between camera frames";
  return j.dump();
}

}  // namespace tactile::mapping
