// Point location in a strain field: which triangle holds a point.

#include <cmath>

#include "tactile/mapping/strain_field.hpp"

namespace tactile::mapping {
namespace {

// Barycentric test with a tolerance of a few ulps of the triangle's size, so that points on a
// shared edge (contactor grids often fall exactly on the landmarks' lattice in synthetic data)
// find one of the two triangles instead of neither.
bool contains(const FieldTriangle& t, double x, double y) {
  const auto& a = t.vertex_mm[0];
  const auto& b = t.vertex_mm[1];
  const auto& c = t.vertex_mm[2];
  const double det = (b.x_mm - a.x_mm) * (c.y_mm - a.y_mm) - (c.x_mm - a.x_mm) * (b.y_mm - a.y_mm);
  if (det == 0) return false;
  const double l1 = ((x - a.x_mm) * (c.y_mm - a.y_mm) - (c.x_mm - a.x_mm) * (y - a.y_mm)) / det;
  const double l2 = ((b.x_mm - a.x_mm) * (y - a.y_mm) - (x - a.x_mm) * (b.y_mm - a.y_mm)) / det;
  constexpr double kTolerance = 1e-9;
  return l1 >= -kTolerance && l2 >= -kTolerance && l1 + l2 <= 1.0 + kTolerance;
}

}  // namespace

std::optional<StrainTensor> sample(const StrainField& field, double x_mm, double y_mm) {
  const auto& bins = field.bins;
  if (bins.bins_x <= 0 || bins.bins_y <= 0 || !std::isfinite(x_mm) || !std::isfinite(y_mm)) {
    return std::nullopt;
  }
  const double fx = (x_mm - bins.x0_mm) / bins.bin_size_mm;
  const double fy = (y_mm - bins.y0_mm) / bins.bin_size_mm;
  // A point just past the last bin edge may still lie on the hull; the clamp below catches it, and
  // anything further out is outside every triangle's bounding box.
  constexpr double kSlack = 1e-6;
  if (fx < -kSlack || fy < -kSlack || fx > bins.bins_x + kSlack || fy > bins.bins_y + kSlack) {
    return std::nullopt;
  }
  const auto bx = std::min(static_cast<std::int32_t>(std::max(fx, 0.0)), bins.bins_x - 1);
  const auto by = std::min(static_cast<std::int32_t>(std::max(fy, 0.0)), bins.bins_y - 1);
  const auto b = static_cast<std::size_t>(by) * bins.bins_x + bx;
  for (auto i = bins.bin_start[b]; i < bins.bin_start[b + 1]; ++i) {
    const auto& t =
        field.triangles[static_cast<std::size_t>(bins.triangle_index[static_cast<std::size_t>(i)])];
    if (contains(t, x_mm, y_mm)) return t.strain;
  }
  return std::nullopt;
}

}  // namespace tactile::mapping
