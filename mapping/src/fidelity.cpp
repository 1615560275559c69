// Fidelity metrics of a mapped movie against its source strain.

#include "tactile/mapping/fidelity.hpp"
#include "tactile/common/stats.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "tactile/mapping/methods.hpp"

namespace tactile::mapping {
namespace {}  // namespace

FidelityMetrics fidelity(const movie::TactileMovie& movie, const capture::StrainMovie& source,
                         const Placement& placement, double um_per_strain,
                         double slew_limit_um_per_s, const StrainFieldOptions& field_options) {
  if (!(um_per_strain > 0) || !std::isfinite(um_per_strain)) {
    throw std::invalid_argument(
        fmt::format("fidelity: um_per_strain {} must be positive", um_per_strain));
  }
  movie::validate_movie(movie);
  const auto& layout = movie.layout;
  const auto n = static_cast<std::size_t>(layout.contactor_count());
  const auto frames = static_cast<std::size_t>(movie.frame_count);
  FidelityMetrics m;

  const bool along_x = layout.axis == movie::DeflectionAxis::x;
  const double pitch_mm = along_x ? layout.pitch_x_mm : layout.pitch_y_mm;
  const auto dir = deflection_direction(layout, placement);
  const auto positions = contactor_positions_mm(layout, placement);
  struct Pair {
    std::size_t a, b;
    double x_mm, y_mm;
  };
  std::vector<Pair> pairs;
  for (std::int32_t r = 0; r < layout.rows; ++r) {
    for (std::int32_t c = 0; c < layout.cols; ++c) {
      const std::int32_t r2 = along_x ? r : r + 1;
      const std::int32_t c2 = along_x ? c + 1 : c;
      if (r2 >= layout.rows || c2 >= layout.cols) continue;
      const auto a = static_cast<std::size_t>(r * layout.cols + c);
      const auto b = static_cast<std::size_t>(r2 * layout.cols + c2);
      pairs.push_back({a, b, (positions[a].x_mm + positions[b].x_mm) / 2,
                       (positions[a].y_mm + positions[b].y_mm) / 2});
    }
  }
  std::vector<capture::PointMm> needed;
  for (const auto& p : pairs) needed.push_back({p.x_mm, p.y_mm});
  std::vector<double> imposed, wanted;
  if (frames > 0 && !source.frames.empty()) {
    const double t0 = source.frames.front().t_s;
    for (const auto& sf : source.frames) {
      const double index = std::round((sf.t_s - t0) * movie.rate_hz);
      if (index < 0 || index >= static_cast<double>(frames)) continue;
      const auto frame = movie.frame(static_cast<std::int32_t>(index));
      const auto field = build_strain_field(sf, field_options, needed);
      for (const auto& p : pairs) {
        const auto e = sample(field, p.x_mm, p.y_mm);
        if (!e) continue;
        wanted.push_back(normal_strain(*e, dir.x_mm, dir.y_mm));
        imposed.push_back((frame[p.b] - frame[p.a]) / (pitch_mm * um_per_strain));
      }
    }
  }
  m.compared_pairs = static_cast<std::int64_t>(imposed.size());
  if (!imposed.empty()) {
    double se = 0, ss = 0;
    for (std::size_t i = 0; i < imposed.size(); ++i) {
      se += (imposed[i] - wanted[i]) * (imposed[i] - wanted[i]);
      ss += wanted[i] * wanted[i];
    }
    m.strain_rms_error = std::sqrt(se / static_cast<double>(imposed.size()));
    m.source_strain_rms = std::sqrt(ss / static_cast<double>(imposed.size()));
    m.strain_correlation = pearson(imposed, wanted);
  }

  if (frames > 0 && n > 0) {
    std::size_t saturated = 0, slewed = 0, steps = 0, accels = 0;
    double acc2 = 0, d2 = 0;
    for (std::size_t f = 0; f < frames; ++f) {
      for (std::size_t j = 0; j < n; ++j) {
        const double d = movie.deflection_um[f * n + j];
        d2 += d * d;
        if (at_deflection_limit(layout, d)) ++saturated;
        if (f >= 1) {
          ++steps;
          if (at_slew_limit(d - movie.deflection_um[(f - 1) * n + j], slew_limit_um_per_s,
                            movie.rate_hz)) {
            ++slewed;
          }
        }
        if (f >= 2) {
          const double a = (d - 2.0 * movie.deflection_um[(f - 1) * n + j] +
                            movie.deflection_um[(f - 2) * n + j]) *
                           movie.rate_hz * movie.rate_hz;
          acc2 += a * a;
          ++accels;
        }
      }
    }
    m.saturated_fraction = static_cast<double>(saturated) / static_cast<double>(frames * n);
    m.rms_deflection_um = std::sqrt(d2 / static_cast<double>(frames * n));
    if (steps > 0)
      m.slew_limited_fraction = static_cast<double>(slewed) / static_cast<double>(steps);
    if (accels > 0) m.rms_acceleration_um_per_s2 = std::sqrt(acc2 / static_cast<double>(accels));
  }
  return m;
}

namespace {
constexpr double kLimitToleranceUm = 1e-3;
}  // namespace

bool at_deflection_limit(const movie::Layout& layout, double d_um) {
  const double lo = layout.deflection_min_um, hi = layout.deflection_max_um;
  return (lo != 0 && std::abs(d_um - lo) <= kLimitToleranceUm) ||
         (hi != 0 && std::abs(d_um - hi) <= kLimitToleranceUm);
}

bool at_slew_limit(double step_um, double slew_limit_um_per_s, double rate_hz) {
  return std::abs(step_um) >= slew_limit_um_per_s / rate_hz - kLimitToleranceUm;
}

std::string describe_fidelity(const FidelityMetrics& fit) {
  return fmt::format(
      "fidelity to the measured strain: correlation {:.3f}, RMS error {:.3g} against RMS {:.3g} "
      "({} samples)",
      fit.strain_correlation, fit.strain_rms_error, fit.source_strain_rms, fit.compared_pairs);
}

}  // namespace tactile::mapping
