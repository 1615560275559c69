// Registration of the contactor grid on the strain field.

#include <algorithm>
#include <cmath>
#include <limits>

#include "tactile/mapping/placement.hpp"

namespace tactile::mapping {

Placement default_placement(const capture::StrainMovie& movie) {
  Placement placement;
  const auto& cal = movie.calibration;
  if (cal.image_width_px > 0 && cal.image_height_px > 0) {
    // The image centre through the calibration: the same as half the field size when the
    // calibration's origin is the image corner, and still right when it is not.
    const auto centre =
        capture::to_mm(cal, (cal.image_width_px - 1) / 2.0, (cal.image_height_px - 1) / 2.0);
    placement.centre_x_mm = centre.x_mm;
    placement.centre_y_mm = centre.y_mm;
    return placement;
  }
  if (movie.field_width_mm > 0 && movie.field_height_mm > 0) {
    placement.centre_x_mm = movie.field_width_mm / 2;
    placement.centre_y_mm = movie.field_height_mm / 2;
    return placement;
  }
  // No stated field of view: the middle of whatever was measured.
  double x_min = std::numeric_limits<double>::infinity();
  double x_max = -x_min;
  double y_min = x_min;
  double y_max = -x_min;
  const auto extend = [&](const capture::TrackedPoint& p) {
    x_min = std::min(x_min, p.x_mm);
    x_max = std::max(x_max, p.x_mm);
    y_min = std::min(y_min, p.y_mm);
    y_max = std::max(y_max, p.y_mm);
  };
  for (const auto& p : movie.tracks) extend(p);
  if (movie.tracks.empty()) {
    for (const auto& f : movie.frames) {
      for (const auto& p : f.points_from) extend(p);
    }
  }
  if (x_min <= x_max && y_min <= y_max) {
    placement.centre_x_mm = (x_min + x_max) / 2;
    placement.centre_y_mm = (y_min + y_max) / 2;
  }
  return placement;
}

capture::PointMm contactor_position_mm(const movie::Layout& layout, const Placement& placement,
                                       std::int32_t row, std::int32_t col) {
  const double u = (col - (layout.cols - 1) / 2.0) * layout.pitch_x_mm * placement.scale;
  const double v = (row - (layout.rows - 1) / 2.0) * layout.pitch_y_mm * placement.scale;
  const double c = std::cos(placement.rotation_rad);
  const double s = std::sin(placement.rotation_rad);
  return {placement.centre_x_mm + c * u - s * v, placement.centre_y_mm + s * u + c * v};
}

std::vector<capture::PointMm> contactor_positions_mm(const movie::Layout& layout,
                                                     const Placement& placement) {
  std::vector<capture::PointMm> positions;
  positions.reserve(static_cast<std::size_t>(std::max(layout.contactor_count(), 0)));
  for (std::int32_t r = 0; r < layout.rows; ++r) {
    for (std::int32_t c = 0; c < layout.cols; ++c) {
      positions.push_back(contactor_position_mm(layout, placement, r, c));
    }
  }
  return positions;
}

}  // namespace tactile::mapping
