#pragma once
// Strain maps as the first paper draws them: every Delaunay edge of a strain frame, coloured from
// black (most compressed) through grey (unchanged) to white (most stretched), with the scale
// printed on the image.

#include <filesystem>

#include "tactile/capture/strain_movie.hpp"

namespace tactile::capture {

struct StrainMapOptions {
  // |rel_change| drawn as pure black / white; larger values saturate. 0 = strain_map_full_scale.
  double full_scale = 0;
  int line_width_px = 2;
};

// The 99th percentile of |rel_change| over every edge of the movie, so that one scale serves a
// whole sequence of maps and a few outliers do not wash the rest out. 0 for a movie without edges.
double strain_map_full_scale(const StrainMovie& movie);

// Draws `frame`'s edges at their frame_to pixel positions on an image the size given by the
// calibration. Throws std::invalid_argument for an edge naming a track that is not a point of the
// frame or for a non-positive scale, std::runtime_error naming the file if it cannot be written.
void write_strain_map_png(const std::filesystem::path& path, const StrainFrame& frame,
                          const Calibration& calibration, const StrainMapOptions& options);

}  // namespace tactile::capture
