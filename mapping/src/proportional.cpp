// "proportional" mapping: deflection = gain * local normal strain along the deflection axis.

#include <cmath>

#include "tactile/mapping/methods.hpp"

namespace tactile::mapping {

capture::PointMm deflection_direction(const movie::Layout& layout, const Placement& placement) {
  const double c = std::cos(placement.rotation_rad);
  const double s = std::sin(placement.rotation_rad);
  // The layout's unit x is (c, s) in the field, its unit y is (-s, c): see contactor_position_mm.
  if (layout.axis == movie::DeflectionAxis::x) return {c, s};
  return {-s, c};
}

std::vector<capture::PointMm> sample_points_mm(const movie::Layout& layout,
                                               const Placement& placement) {
  auto points = contactor_positions_mm(layout, placement);
  const bool along_x = layout.axis == movie::DeflectionAxis::x;
  const auto cols = static_cast<std::size_t>(layout.cols);
  const std::size_t n = points.size();
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t r = i / cols, c = i % cols;
    const bool last = along_x ? c + 1 >= cols : r + 1 >= static_cast<std::size_t>(layout.rows);
    if (last) continue;
    const auto& a = points[i];
    const auto& b = points[along_x ? i + 1 : i + cols];
    points.push_back({(a.x_mm + b.x_mm) / 2, (a.y_mm + b.y_mm) / 2});
  }
  return points;
}

std::vector<double> proportional_frame(const StrainField& field, const movie::Layout& layout,
                                       const Placement& placement, double gain_um_per_strain) {
  const auto n = deflection_direction(layout, placement);
  const auto positions = contactor_positions_mm(layout, placement);
  std::vector<double> deflection_um(positions.size(), 0.0);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    if (const auto e = sample(field, positions[i].x_mm, positions[i].y_mm)) {
      deflection_um[i] = gain_um_per_strain * normal_strain(*e, n.x_mm, n.y_mm);
    }
  }
  return deflection_um;
}

}  // namespace tactile::mapping
