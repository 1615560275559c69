#pragma once
// Exact strain movies of capture's synthetic scenes (no images, no measurement noise): the
// reference every measured or mapped movie can be scored against.

#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/synth.hpp"

namespace tactile::capture {

// A material grid of skin points (spacing grid_spacing_mm, in skin coordinates) followed through
// the scene with skin_to_image. tracks: every point at every frame where it is in view
// and touches the glass. frames: one per consecutive frame pair, the points in contact in both,
// triangulated on the grid (two triangles per grid square); no edges, so the strain field measures
// them from the exact positions. Throws std::invalid_argument for a bad spec (validate)
// or a non-positive spacing.
StrainMovie ground_truth_strain_movie(const SceneSpec& spec, double grid_spacing_mm);

}  // namespace tactile::capture
