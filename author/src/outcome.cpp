// A mapping with its figures for the authoring window; see outcome.hpp.
#include "tactile/author/outcome.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "tactile/common/parallel_for.hpp"
#include "tactile/common/version.hpp"

namespace tactile::author {

namespace {

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The display frames [first, last] of `movie` as a movie of their own.
movie::TactileMovie frames_of(const movie::TactileMovie& movie, std::int32_t first,
                              std::int32_t last) {
  movie::TactileMovie part;
  part.layout = movie.layout;
  part.rate_hz = movie.rate_hz;
  part.frame_count = last - first + 1;
  const auto n = static_cast<std::size_t>(movie.layout.contactor_count());
  part.deflection_um.assign(
      movie.deflection_um.begin() + static_cast<std::ptrdiff_t>(first * n),
      movie.deflection_um.begin() + static_cast<std::ptrdiff_t>((last + 1) * n));
  return part;
}

// The stretches of the strain frames over_time covers, and the display frames of each (as
// fidelity() pairs them: the display frame nearest each strain frame's time since the first).
struct Stretch {
  std::int32_t f0 = 0, f1 = 0;  // strain frames, inclusive
  std::int32_t d0 = 0, d1 = 0;  // display frames, inclusive
};

std::vector<Stretch> stretches_of(const capture::StrainMovie& source,
                                  const movie::TactileMovie& movie) {
  std::vector<Stretch> out;
  const auto frames = static_cast<std::int32_t>(source.frames.size());
  const int count = std::min(kFidelityStretches, frames);
  if (count <= 0 || movie.frame_count <= 0) return out;
  const double t0 = source.frames.front().t_s;
  const auto display_index = [&](double t_s) {
    return std::clamp(static_cast<std::int32_t>(std::lround((t_s - t0) * movie.rate_hz)), 0,
                      movie.frame_count - 1);
  };
  for (int k = 0; k < count; ++k) {
    Stretch s;
    s.f0 = k * frames / count;
    s.f1 = (k + 1) * frames / count - 1;
    if (s.f1 < s.f0) continue;
    s.d0 = display_index(source.frames[static_cast<std::size_t>(s.f0)].t_s);
    // Up to the frame before the next stretch's first, so that the stretches tile the movie.
    s.d1 = k + 1 < count
               ? std::max(s.d0,
                          display_index(source.frames[static_cast<std::size_t>(s.f1 + 1)].t_s) - 1)
               : movie.frame_count - 1;
    out.push_back(s);
  }
  return out;
}

FidelityPoint stretch_fidelity(const MappingOutcome& o, const capture::StrainMovie& source,
                               const Stretch& s, const mapping::Placement& placement,
                               double um_per_strain) {
  capture::StrainMovie slice;
  slice.frame_rate_hz = source.frame_rate_hz;
  slice.span_frames = source.span_frames;
  slice.calibration = source.calibration;
  slice.field_width_mm = source.field_width_mm;
  slice.field_height_mm = source.field_height_mm;
  slice.frames.assign(source.frames.begin() + s.f0, source.frames.begin() + s.f1 + 1);
  const mapping::FidelityMetrics m =
      mapping::fidelity(frames_of(o.movie, s.d0, s.d1), slice, placement, um_per_strain,
                        o.params.slew_limit_um_per_s, o.params.field);
  const double t0 = source.frames.front().t_s;
  return {slice.frames.front().t_s - t0, slice.frames.back().t_s - t0,
          m.strain_correlation,          m.strain_rms_error,
          m.saturated_fraction,          m.slew_limited_fraction};
}

}  // namespace

MappingOutcome map_for_authoring(const capture::StrainMovie& strain,
                                 const mapping::MapRequest& request) {
  MappingOutcome o;
  o.request = request;
  try {
    const mapping::ResolvedMap resolved = mapping::resolve(request, OptionSpelling::cli);
    o.layout = resolved.layout;
    o.params = resolved.params;
    o.params.program_version = kVersion;
    if (strain.frames.empty()) throw std::invalid_argument("the strain movie has no strain frames");
    const auto t0 = std::chrono::steady_clock::now();
    const capture::StrainMovie source = mapping::strain_source(strain, o.params);
    mapping::MappingResult mapped = mapping::map_strain_frames(source, o.layout, o.params);
    o.map_ms = ms_since(t0);
    o.movie = std::move(mapped.movie);
    const auto t1 = std::chrono::steady_clock::now();
    if (mapped.um_per_strain > 0) {
      // The whole movie's figures and each stretch's, on every core: a change waits for them.
      const std::vector<Stretch> stretches = stretches_of(source, o.movie);
      o.over_time.resize(stretches.size());
      parallel_for(stretches.size() + 1, 0, [&](std::size_t i) {
        if (i == 0) {
          o.metrics = mapping::fidelity(o.movie, source, mapped.placement, mapped.um_per_strain,
                                        o.params.slew_limit_um_per_s, o.params.field);
        } else {
          o.over_time[i - 1] =
              stretch_fidelity(o, source, stretches[i - 1], mapped.placement, mapped.um_per_strain);
        }
      });
    }
    const auto n = static_cast<std::size_t>(o.layout.contactor_count());
    o.saturated_share.assign(n, 0);
    o.slew_limited_share.assign(n, 0);
    const auto frames = static_cast<std::size_t>(o.movie.frame_count);
    for (std::size_t f = 0; f < frames; ++f) {
      for (std::size_t j = 0; j < n; ++j) {
        const double d = o.movie.deflection_um[f * n + j];
        if (mapping::at_deflection_limit(o.layout, d)) o.saturated_share[j] += 1;
        if (f > 0 && mapping::at_slew_limit(d - o.movie.deflection_um[(f - 1) * n + j],
                                            o.params.slew_limit_um_per_s, o.movie.rate_hz)) {
          o.slew_limited_share[j] += 1;
        }
      }
    }
    for (std::size_t j = 0; j < n; ++j) {
      o.saturated_share[j] /= static_cast<float>(std::max<std::size_t>(frames, 1));
      o.slew_limited_share[j] /= static_cast<float>(std::max<std::size_t>(frames, 2) - 1);
    }
    o.figures_ms = ms_since(t1);
  } catch (const std::exception& e) {
    MappingOutcome failed;
    failed.request = request;
    failed.error = e.what();
    return failed;
  }
  return o;
}

std::vector<FigureRow> compare_figures(const MappingOutcome& a, const MappingOutcome& b) {
  return {
      {"correlation", a.metrics.strain_correlation, b.metrics.strain_correlation},
      {"RMS error", a.metrics.strain_rms_error, b.metrics.strain_rms_error},
      {"saturated %", 100 * a.metrics.saturated_fraction, 100 * b.metrics.saturated_fraction},
      {"slew-limited %", 100 * a.metrics.slew_limited_fraction,
       100 * b.metrics.slew_limited_fraction},
      {"map ms", a.map_ms, b.map_ms},
  };
}

std::string describe_change(const mapping::MapRequest& a, const mapping::MapRequest& b) {
  std::string out;
  for (const auto& row : mapping::map_options()) {
    if (row.positional) continue;
    const std::string va = row.shown(a), vb = row.shown(b);
    if (va == vb) continue;
    if (!out.empty()) out += ", ";
    out += fmt::format("{} {} -> {}", option_label(row.name, OptionSpelling::cli),
                       va.empty() ? "(default)" : va, vb.empty() ? "(default)" : vb);
  }
  return out.empty() ? "same mapping" : out;
}

}  // namespace tactile::author
