#pragma once
// Synthetic strain movies with a known deformation, for the mapping tests. The landmarks sit on a
// (optionally jittered) regular grid triangulated by splitting each grid square along a diagonal,
// so the tests depend on neither the capture module's triangulation nor its tracking.

#include <cstdint>
#include <functional>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping::testing {

// Displacement (mm) of the skin point at reference position (x_mm, y_mm) at the frame's time.
using Displacement = std::function<capture::PointMm(double x_mm, double y_mm, double t_s)>;

struct GridSpec {
  double width_mm = 10.0;
  double height_mm = 10.0;
  double spacing_mm = 0.5;
  double jitter_fraction = 0.0;  // uniform jitter of each landmark, as a fraction of the spacing
  std::uint32_t seed = 1;
};

// One StrainFrame: the landmarks at their reference positions (points_from) and displaced by
// `displacement` at time t_s (points_to); edges carry the exact relative length changes.
capture::StrainFrame make_frame(const GridSpec& grid, const Displacement& displacement, double t_s,
                                std::int32_t frame_from, std::int32_t frame_to);

// A movie of `frames` StrainFrames at camera frames 1..frames (t_s = k / frame_rate_hz), each
// measuring the displacement at its own time against the reference grid.
capture::StrainMovie make_movie(const GridSpec& grid, const Displacement& displacement,
                                std::int32_t frames, double frame_rate_hz = 60.0);

// Fills movie.tracks from the frames' points, ordered by track, as the strain movie file wants
// every point's track in /tracks.
void add_tracks(capture::StrainMovie& movie);

// A layout built by hand, so these tests do not depend on display's built-in layouts.
movie::Layout grid_layout(std::int32_t rows, std::int32_t cols, double pitch_x_mm,
                          double pitch_y_mm, movie::DeflectionAxis axis = movie::DeflectionAxis::x);

// Default parameters with method "proportional", for the tests of that method.
inline MappingParams proportional_params() {
  MappingParams p;
  p.method = MappingMethod::proportional;
  return p;
}

}  // namespace tactile::mapping::testing
