#pragma once
// Strain accumulated from a reference frame along the tracks (Lagrangian).
//
// A StrainFrame of `tactile capture` holds the strain between two nearby camera frames
// (frame-to-frame, or over a span of k frames). Summing those at fixed image positions is not the
// strain the skin has accumulated when it slides: the skin flows through the image, so each sum
// mixes different pieces of skin. Following the tracks instead gives the true accumulated strain:
// for every track alive at both the reference frame R and frame f, its smoothed position at R and
// at f; the Delaunay triangulation of the positions at R (capture::triangulate_strain, same
// max_edge_ratio rule as the capture); each edge's relative length change from R to f.
//
// The result is an ordinary StrainMovie whose frame k has frame_from = R and frame_to = f, so the
// whole mapping applies unchanged. Its fields live on the reference positions: a contactor placed
// at (x, y) follows the piece of skin that was at (x, y) in frame R (Lagrangian sampling).

#include <cstdint>

#include "tactile/capture/strain_movie.hpp"

namespace tactile::mapping {

struct AccumulateOptions {
  // Camera frame of the reference; -1 = the first frame of the movie's first StrainFrame.
  std::int32_t reference_frame = -1;
  // Edges longer than this multiple of the frame's median edge are hull slivers (as in capture).
  double max_edge_ratio = 3.0;
};

// One StrainFrame per camera frame f after the reference for which at least three tracks are
// alive at both R and f (t_s = f / frame_rate_hz). Throws std::invalid_argument when the movie has
// no tracks, a reference frame outside [0, camera_frame_count), or a non-positive frame rate.
// The last camera frame a reference can be: the movie's last frame, or a later tracked one.
std::int32_t last_reference_frame(const capture::StrainMovie& movie);

capture::StrainMovie accumulate_along_tracks(const capture::StrainMovie& movie,
                                             const AccumulateOptions& options = {});

}  // namespace tactile::mapping
