#pragma once
// Registration: where the contactor grid sits on the strain field.
//
// The field lives in the camera's image plane (mm, x right, y down). The contactor grid is placed
// by its centre, a rotation (counter-clockwise in the x-right/y-down frame as drawn on screen:
// positive angles turn +x towards +y) and a scale (1 = physical size: one millimetre of contactor
// pitch samples one millimetre of skin). The grid stays fixed in the image plane for the whole
// movie (Eulerian sampling); following the skin (Lagrangian) is `strain = accumulated`.

#include <cstdint>
#include <vector>

#include "tactile/capture/strain_movie.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::mapping {

struct Placement {
  double centre_x_mm = 0;
  double centre_y_mm = 0;
  double rotation_rad = 0;
  double scale = 1;  // field millimetres per layout millimetre
};

// Centred on the field of view at physical size: on the image centre mapped through the movie's
// calibration when it states an image size (for a calibration with its origin at the image corner
// that is (field_width_mm / 2, field_height_mm / 2)); else on (field_width_mm / 2,
// field_height_mm / 2); else, when the movie states no field size, on the bounding box of its
// tracked points.
Placement default_placement(const capture::StrainMovie& movie);

// Field position of contactor (row, col). The grid centre is the midpoint between the corner
// contactors; contactor (r, c) sits at ((c - (cols - 1) / 2) * pitch_x, (r - (rows - 1) / 2) *
// pitch_y) from it, scaled and rotated.
capture::PointMm contactor_position_mm(const movie::Layout& layout, const Placement& placement,
                                       std::int32_t row, std::int32_t col);

// The same for every contactor, row-major.
std::vector<capture::PointMm> contactor_positions_mm(const movie::Layout& layout,
                                                     const Placement& placement);

}  // namespace tactile::mapping
