// Point location in a strain field: which triangle holds a point.

#include <cmath>

#include "tactile/mapping/strain_field.hpp"

namespace tactile::mapping {
bool triangle_contains(const std::array<capture::PointMm, 3>& v, double x, double y) {
  // Barycentric test with a tolerance of a few ulps of the triangle's size, so that points on a
  // shared edge (contactor grids often fall exactly on the landmarks' lattice in synthetic data)
  // find one of the two triangles instead of neither.
  const auto& a = v[0];
  const auto& b = v[1];
  const auto& c = v[2];
  const double det = (b.x_mm - a.x_mm) * (c.y_mm - a.y_mm) - (c.x_mm - a.x_mm) * (b.y_mm - a.y_mm);
  if (det == 0) return false;
  const double l1 = ((x - a.x_mm) * (c.y_mm - a.y_mm) - (c.x_mm - a.x_mm) * (y - a.y_mm)) / det;
  const double l2 = ((b.x_mm - a.x_mm) * (y - a.y_mm) - (x - a.x_mm) * (b.y_mm - a.y_mm)) / det;
  constexpr double kTolerance = 1e-9;
  return l1 >= -kTolerance && l2 >= -kTolerance && l1 + l2 <= 1.0 + kTolerance;
}

std::optional<StrainTensor> sample(const StrainField& field, double x_mm, double y_mm) {
  std::optional<StrainTensor> found;
  for_each_candidate(field.bins, x_mm, y_mm, [&](std::int32_t i) {
    const auto& t = field.triangles[static_cast<std::size_t>(i)];
    if (!triangle_contains(t.vertex_mm, x_mm, y_mm)) return false;
    found = t.strain;
    return true;
  });
  return found;
}

}  // namespace tactile::mapping
