#pragma once
// Ground-truth skin strain of the simulated fingertip (paper 2's scenes) as a StrainMovie, so the
// tactile-movie mappings can be judged by the perception evaluation: the same trials (feature,
// procedure, seed, variation) and contact mechanics as simulate_trial, seen as the skin's
// stretch instead of the sensor's channels. Assumptions in docs/perception-models.md
// ("Skin strain").

#include <cstdint>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/perception/sensor_model.hpp"

namespace tactile::experiments {

struct SkinStrainOptions {
  // Material grid over the pad (pad coordinates: x distal, y ulnar, mm from the pad's centre):
  // nodes every grid_spacing_mm over [-half_length_mm, half_length_mm] x [-half_width_mm,
  // half_width_mm]. The movie's field is that rectangle shifted to start at (0, 0), so the
  // default placement of a contactor grid centres it on the pad's centre.
  double grid_spacing_mm = 1.0;
  double half_length_mm = 10.0;
  double half_width_mm = 7.0;
  // false: strain from each 100 Hz frame to the next (like `tactile capture`); true: strain from
  // the first frame (free air, the skin at rest) to each later frame (like the mapping's
  // "accumulated" strain).
  bool from_rest = false;
  // Lateral skin displacement in the sliding direction per mm of local indentation while the
  // plate slides under the pad (friction dragging the skin; see the docs).
  double drag_per_mm = 0.3;
  double drag_build_up_mm = 1.0;  // sliding distance over which the drag builds up
};

// Strain frames at the sensor's row rate (100 Hz) for the whole trial, t_s = frame / 100.
// Each StrainFrame holds every grid node at both frames (track id = node index, positions = the
// skin's lateral position), the grid's edges (horizontal, vertical, one diagonal per cell) with
// the relative change of their length on the indented (3-D) skin surface, and two triangles per
// cell. No tracks are stored. Throws std::invalid_argument for a non-positive grid spacing or
// extent.
capture::StrainMovie simulate_skin_strain(const perception::SurfaceFeature& feature,
                                          perception::Procedure procedure, std::uint64_t seed,
                                          const perception::SensorModel& model = {},
                                          const SkinStrainOptions& options = {});

}  // namespace tactile::experiments
