#pragma once
// Fidelity of a mapped movie: how well the strain it imposes on the finger follows the source.
//
// Imposed strain between neighbouring contactors c and c+1 along the deflection axis, at display
// frame i:  (d[c+1] - d[c]) / (pitch_along_axis_mm * um_per_strain), with um_per_strain the
// gain the mapping actually used (MappingResult::um_per_strain, normalisation included), so a
// movie that reproduces the skin exactly has imposed == source. Source strain: the normal strain
// along the deflection axis of the source's strain field at the pair's midpoint (placement
// applied), for every StrainFrame, compared with the display frame nearest its time. Pairs whose
// midpoint is masked are left out. The same comparison is fair for every method: "proportional"
// does not aim at neighbour differences and is expected to score lower.

#include <cstdint>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/mapping/placement.hpp"
#include "tactile/mapping/strain_field.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

struct FidelityMetrics {
  std::int64_t compared_pairs = 0;  // (pair, strain frame) samples compared
  double strain_rms_error = 0;      // RMS of imposed - source strain (dimensionless)
  double source_strain_rms = 0;     // RMS of the source strain at the same samples (for scale)
  // Pearson correlation of imposed and source strain; 0 when either has no variance.
  double strain_correlation = 0;
  // Fraction of contactor-frames at a limit of the deflection range (within 1e-3 um), over the
  // whole movie; a limit at 0 does not count (neutral is not saturation).
  double saturated_fraction = 0;
  // RMS over contactors and frames of the second time difference of deflection, as an
  // acceleration (um/s^2): low = smooth.
  double rms_acceleration_um_per_s2 = 0;
  // Fraction of frame steps whose |change| reaches the slew limit (within 1e-3 um).
  double slew_limited_fraction = 0;
  // RMS over contactors and frames of the deflection (um): how much the movie moves at all.
  double rms_deflection_um = 0;
};

// Throws std::invalid_argument for um_per_strain <= 0 or an inconsistent movie.
FidelityMetrics fidelity(const movie::TactileMovie& movie, const capture::StrainMovie& source,
                         const Placement& placement, double um_per_strain,
                         double slew_limit_um_per_s, const StrainFieldOptions& field = {});

// The rules saturated_fraction and slew_limited_fraction count by (within 1e-3 um), for views
// that show where a movie saturates or is slew-limited: a deflection at a non-zero end of the
// layout's range; a frame-to-frame step as large as the slew limit allows.
bool at_deflection_limit(const movie::Layout& layout, double d_um);
bool at_slew_limit(double step_um, double slew_limit_um_per_s, double rate_hz);

// "fidelity to the measured strain: correlation 0.998, RMS error ... (N samples)", as `map` and
// `demo` print it.
std::string describe_fidelity(const FidelityMetrics& fit);

}  // namespace tactile::mapping
