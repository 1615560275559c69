#pragma once
// Mapping methods: one strain field -> one frame of contactor deflections (micrometres,
// row-major), before normalisation, time resampling and limits. Each method samples the field at
// field positions given by the placement; masked samples contribute nothing (see each method).

#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/mapping/placement.hpp"
#include "tactile/mapping/strain_field.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

// Unit vector of the layout's deflection axis in field coordinates (the layout's x or y turned
// by the placement's rotation).
capture::PointMm deflection_direction(const movie::Layout& layout, const Placement& placement);

// Every field position a method may sample: the contactors and the midpoints between neighbours
// along the deflection axis. The field needs to be built only there (build_strain_field only_at).
std::vector<capture::PointMm> sample_points_mm(const movie::Layout& layout,
                                               const Placement& placement);

// "proportional": each contactor deflects by gain_um_per_strain * e_axis, where e_axis is the
// normal strain along the deflection axis at the contactor's position. Stretch (e > 0) pushes
// towards +axis. Assumes the skin under one contactor is summarised by its local strain; ignores
// strain between contactors. Masked contactors stay neutral (0).
std::vector<double> proportional_frame(const StrainField& field, const movie::Layout& layout,
                                       const Placement& placement, double gain_um_per_strain);

// "integrated": along every line of contactors parallel to the deflection axis, neighbouring
// deflections differ by the skin's extension between them:
//   d[k+1] - d[k] = gain_um_per_strain * e_axis(midpoint) * pitch_along_axis_mm,
// so gain_um_per_strain = 1000 reproduces the measured strain on the display surface. The
// overdetermined-or-not system of each line is solved by minimum-norm least squares (Eigen,
// complete orthogonal decomposition): differences with a masked midpoint are dropped, each
// connected run of contactors comes out zero-mean, and isolated contactors stay neutral. The
// deflection range is applied afterwards by the common clamp (a range-constrained solve is issue
// 5).
std::vector<double> integrated_frame(const StrainField& field, const movie::Layout& layout,
                                     const Placement& placement, double gain_um_per_strain);

}  // namespace tactile::mapping
