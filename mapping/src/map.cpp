// The whole mapping: strain fields -> method -> normalisation -> time resampling -> limits.

#include "tactile/mapping/map.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tactile/common/version.hpp"
#include "tactile/mapping/methods.hpp"
#include "tactile/mapping/resample.hpp"

namespace tactile::mapping {
namespace {

using MethodFrame = std::vector<double> (*)(const StrainField&, const display::Layout&,
                                            const Placement&, double);

MethodFrame method_by_name(const std::string& name) {
  if (name == "proportional") return proportional_frame;
  if (name == "integrated") return integrated_frame;
  throw std::invalid_argument(fmt::format("mapping: unknown method '{}'", name));
}

// The |deflection| that "peak" normalisation maps the movie's peak to: the smaller side of a
// range around neutral, so that neither direction saturates.
double peak_target_um(const display::Layout& layout, double fraction) {
  const double lo = layout.deflection_min_um;
  const double hi = layout.deflection_max_um;
  const double side = (lo < 0 && hi > 0) ? std::min(-lo, hi) : std::max(std::abs(lo), std::abs(hi));
  return fraction * side;
}

}  // namespace

display::TactileMovie map_strain_movie(const capture::StrainMovie& movie,
                                       const display::Layout& layout, const MappingParams& params) {
  validate(params, layout);
  if (movie.frames.empty()) {
    throw std::invalid_argument(
        fmt::format("mapping: strain movie '{}' has no strain frames", movie.source));
  }
  for (std::size_t k = 1; k < movie.frames.size(); ++k) {
    if (!(movie.frames[k].t_s > movie.frames[k - 1].t_s)) {
      throw std::invalid_argument(fmt::format(
          "mapping: strain frame {} (camera frame {}) at t = {} s does not follow the previous "
          "one at {} s",
          k, movie.frames[k].frame_to, movie.frames[k].t_s, movie.frames[k - 1].t_s));
    }
  }
  const Placement placement = params.placement.value_or(default_placement(movie));
  const MethodFrame method = method_by_name(params.method);

  TimedFrames camera;
  camera.values_per_frame = layout.contactor_count();
  camera.t_s.reserve(movie.frames.size());
  camera.values.reserve(movie.frames.size() * static_cast<std::size_t>(layout.contactor_count()));
  for (const auto& frame : movie.frames) {
    const auto field = build_strain_field(frame, params.field);
    const auto deflection_um = method(field, layout, placement, params.gain_um_per_strain);
    camera.t_s.push_back(frame.t_s);
    camera.values.insert(camera.values.end(), deflection_um.begin(), deflection_um.end());
  }

  double factor = 1.0;
  if (params.normalisation == "peak") {
    double peak_um = 0;
    for (const double v : camera.values) peak_um = std::max(peak_um, std::abs(v));
    // An all-neutral movie stays neutral rather than dividing by zero.
    if (peak_um > 0) factor = peak_target_um(layout, params.peak_fraction) / peak_um;
    for (double& v : camera.values) v *= factor;
  }

  const auto display_frames = resample_linear(camera, params.rate_hz);

  display::TactileMovie out;
  out.layout = layout;
  out.rate_hz = params.rate_hz;
  out.frame_count = static_cast<std::int32_t>(display_frames.t_s.size());
  out.deflection_um.assign(display_frames.values.begin(), display_frames.values.end());
  out.provenance.program_version =
      params.program_version.empty() ? std::string(kVersion) : params.program_version;
  out.provenance.source = movie.source;
  out.provenance.mapping_method = params.method;
  out.provenance.mapping_parameters_json = parameters_json(params, placement, factor);
  return apply_limits(std::move(out), params.slew_limit_um_per_s);
}

}  // namespace tactile::mapping
