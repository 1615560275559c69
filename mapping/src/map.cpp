// The whole mapping: strain fields -> method -> normalisation -> time resampling -> limits.

#include "tactile/mapping/map.hpp"
#include "tactile/common/stats.hpp"

#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <exception>
#include <stdexcept>

#include "tactile/common/parallel_for.hpp"
#include "tactile/common/provenance.hpp"
#include "tactile/mapping/methods.hpp"
#include "tactile/mapping/resample.hpp"

namespace tactile::mapping {
namespace {

using MethodFrame = std::vector<double> (*)(const StrainField&, const movie::Layout&,
                                            const Placement&, double);

MethodFrame method_frame(MappingMethod method) {
  switch (method) {
    case MappingMethod::proportional:
      return proportional_frame;
    case MappingMethod::integrated:
      return integrated_frame;
    case MappingMethod::profile:
      return nullptr;  // model-driven: no strain field (profile.hpp)
  }
  throw std::invalid_argument("mapping: method out of range");
}

// The |deflection| that "peak" normalisation maps the movie's peak to: the smaller side of a
// range around neutral, so that neither direction saturates.
double peak_target_um(const movie::Layout& layout, double fraction) {
  const double lo = layout.deflection_min_um;
  const double hi = layout.deflection_max_um;
  const double side = (lo < 0 && hi > 0) ? std::min(-lo, hi) : std::max(std::abs(lo), std::abs(hi));
  return fraction * side;
}

double peak_magnitude_um(const std::vector<double>& values) {
  double peak_um = 0;
  for (const double v : values) peak_um = std::max(peak_um, std::abs(v));
  return peak_um;
}

// 99th percentile of the non-neutral |deflections|: one badly tracked triangle then cannot shrink
// the whole movie, at the price of clamping the top percent. Masked contactors (exactly 0) are
// left out so a mostly unmeasured grid does not inflate the gain.
double p99_magnitude_um(const std::vector<double>& values) {
  std::vector<double> magnitude;
  magnitude.reserve(values.size());
  for (const double v : values) {
    if (v != 0) magnitude.push_back(std::abs(v));
  }
  return quantile(std::move(magnitude), 0.99);
}

}  // namespace

capture::StrainMovie strain_source(const capture::StrainMovie& movie, const MappingParams& params) {
  if (params.strain == StrainMode::accumulated)
    return accumulate_along_tracks(movie, params.accumulate);
  return movie;
}

MappingResult map_strain_frames(const capture::StrainMovie& movie, const movie::Layout& layout,
                                const MappingParams& requested) {
  const MappingParams params = resolve_mapping_params(requested, layout);
  if (movie.frames.empty()) {
    throw std::invalid_argument(fmt::format("mapping: strain movie '{}' has no strain frames",
                                            origin_of(movie.provenance)));
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
  const MethodFrame method = method_frame(params.method);
  const auto needed = sample_points_mm(layout, placement);

  TimedFrames camera;
  const auto n = static_cast<std::size_t>(layout.contactor_count());
  camera.values_per_frame = layout.contactor_count();
  camera.t_s.resize(movie.frames.size());
  camera.values.resize(movie.frames.size() * n);
  // Frames are independent: each builds its own fields and writes its own rows. Below 16 frames
  // per worker, threads cost more than they save.
  const int workers = std::clamp(
      worker_count(0), 1, static_cast<int>(std::max<std::size_t>(movie.frames.size() / 16, 1)));
  parallel_for(movie.frames.size(), workers, [&](std::size_t k) {
    const auto deflection_um =
        method ? method(build_strain_field(movie.frames[k], params.field, needed), layout,
                        placement, params.gain_um_per_strain)
               : profile_frame(*params.profile, layout, movie.frames[k].t_s,
                               params.gain_um_per_strain);
    camera.t_s[k] = movie.frames[k].t_s;
    std::copy(deflection_um.begin(), deflection_um.end(),
              camera.values.begin() + static_cast<std::ptrdiff_t>(k * n));
  });

  double factor = 1.0;
  if (params.normalisation != Normalisation::none) {
    const double reference_um = params.normalisation == Normalisation::peak
                                    ? peak_magnitude_um(camera.values)
                                    : p99_magnitude_um(camera.values);
    // An all-neutral movie stays neutral rather than dividing by zero.
    if (reference_um > 0) factor = peak_target_um(layout, params.peak_fraction) / reference_um;
    for (double& v : camera.values) v *= factor;
  }

  const auto display_frames = resample_linear(camera, *params.rate_hz);

  movie::TactileMovie out;
  out.layout = layout;
  out.rate_hz = *params.rate_hz;
  out.frame_count = static_cast<std::int32_t>(display_frames.t_s.size());
  out.deflection_um.assign(display_frames.values.begin(), display_frames.values.end());
  // The strain movie's file, if it came from one, is the caller's to name as the input.
  out.provenance =
      make_provenance({}, to_string(params.method), parameters_json(params, placement, factor));
  if (!params.program_version.empty()) out.provenance.program_version = params.program_version;
  MappingResult result;
  result.movie = apply_limits(std::move(out), params.slew_limit_um_per_s);
  result.placement = placement;
  result.normalisation_factor = factor;
  result.um_per_strain = params.gain_um_per_strain * factor;
  return result;
}

movie::TactileMovie map_strain_movie(const capture::StrainMovie& movie, const movie::Layout& layout,
                                     const MappingParams& requested) {
  const MappingParams params = resolve_mapping_params(requested, layout);
  if (params.strain == StrainMode::accumulated) {
    return map_strain_frames(accumulate_along_tracks(movie, params.accumulate), layout, params)
        .movie;
  }
  return map_strain_frames(movie, layout, params).movie;
}

}  // namespace tactile::mapping
