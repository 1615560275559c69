// Strain tensor of one triangle from the relative length changes of its edges.

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <optional>

#include "tactile/mapping/strain_field.hpp"

namespace tactile::mapping {

double normal_strain(const StrainTensor& strain, double nx, double ny) {
  return strain.exx * nx * nx + strain.eyy * ny * ny + 2.0 * strain.exy * nx * ny;
}

double triangle_quality(const std::array<capture::PointMm, 3>& p) {
  const double ax = p[1].x_mm - p[0].x_mm;
  const double ay = p[1].y_mm - p[0].y_mm;
  const double bx = p[2].x_mm - p[0].x_mm;
  const double by = p[2].y_mm - p[0].y_mm;
  const double cx = p[2].x_mm - p[1].x_mm;
  const double cy = p[2].y_mm - p[1].y_mm;
  const double area = 0.5 * std::abs(ax * by - ay * bx);
  const double squares = ax * ax + ay * ay + bx * bx + by * by + cx * cx + cy * cy;
  if (!(squares > 0)) return 0.0;
  return 4.0 * std::sqrt(3.0) * area / squares;
}

std::optional<StrainTensor> triangle_strain(const std::array<capture::PointMm, 3>& p,
                                            const std::array<double, 3>& rel_change,
                                            double min_quality) {
  // The quality test also rejects NaN coordinates (the comparisons fail).
  const double quality = triangle_quality(p);
  if (!(quality >= min_quality) || !(quality > 0)) return std::nullopt;
  Eigen::Matrix3d a;
  Eigen::Vector3d b;
  for (int i = 0; i < 3; ++i) {
    const auto& from = p[static_cast<std::size_t>(i)];
    const auto& to = p[static_cast<std::size_t>((i + 1) % 3)];
    const double dx = to.x_mm - from.x_mm;
    const double dy = to.y_mm - from.y_mm;
    const double length = std::sqrt(dx * dx + dy * dy);
    const double nx = dx / length;
    const double ny = dy / length;
    // n^T E n = exx nx^2 + eyy ny^2 + 2 exy nx ny.
    a.row(i) << nx * nx, ny * ny, 2.0 * nx * ny;
    b(i) = rel_change[static_cast<std::size_t>(i)];
  }
  const Eigen::Vector3d e = a.partialPivLu().solve(b);
  if (!e.allFinite()) return std::nullopt;
  return StrainTensor{e(0), e(1), e(2)};
}

}  // namespace tactile::mapping
