#pragma once
// How one deflection frame looks: contactor rectangles at their rest positions displaced by
// their (magnified) deflection, coloured by the stretch or compression between neighbours.
// Shared by the preview image and the viewer window so both show the same thing.

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tactile/movie/tactile_movie.hpp"

namespace tactile::movie {

struct ContactorShape {
  double x_mm = 0;  // centre, displaced by deflection x magnification
  double y_mm = 0;
  double rest_x_mm = 0;
  double rest_y_mm = 0;
  double width_mm = 0;
  double height_mm = 0;
  double strain = 0;  // dimensionless, + stretch, - compression
};

// Lateral strain at each contactor along the deflection axis: the change of distance to its
// neighbours on that axis relative to the pitch (central difference inside the array,
// one-sided at its edges; 0 for a single contactor along the axis).
std::vector<double> neighbour_strain(const Layout& layout, std::span<const float> frame_um);

// Magnification that draws the largest deflection of the range as 40 % of the pitch along the
// deflection axis: big enough to see, small enough that neighbours never cross.
double auto_magnification(const Layout& layout);

// The same rule applied to the movie's own largest |deflection| instead of the whole range, so
// a movie that uses a fifth of the range is still drawn visibly displaced (the preview's default).
// Falls back to auto_magnification(layout) for a movie that never moves.
double auto_magnification(const TactileMovie& movie);

// Contactor shapes of one frame in millimetres, (0, 0) = rest centre of contactor (0, 0).
std::vector<ContactorShape> frame_shapes(const Layout& layout, std::span<const float> frame_um,
                                         double magnification);

// Placement of the array in a w x h pixel area (y down): pixel = origin + mm * px_per_mm,
// where mm are the ContactorShape coordinates. Leaves room for the largest displacement of
// the layout's range at `magnification` and a 6 % margin on every side.
struct ViewTransform {
  double px_per_mm = 1;
  double origin_x_px = 0;  // where the rest centre of contactor (0, 0) lands
  double origin_y_px = 0;
};
ViewTransform fit_view(const Layout& layout, double magnification, int width_px, int height_px);

// Diverging colour map: blue for compression, white for none, red for stretch, saturating
// at |strain| = full_scale. Returns {r, g, b}.
std::array<std::uint8_t, 3> strain_colour(double strain, double full_scale);

// Largest |strain| over every frame of the movie (0 for a still movie): the colour scale.
double movie_strain_full_scale(const TactileMovie& movie);

}  // namespace tactile::movie
