// "integrated" mapping: least-squares integration of the strain along each contactor line.

#include <Eigen/Dense>
#include <cstdint>

#include "tactile/mapping/methods.hpp"

namespace tactile::mapping {

std::vector<double> integrated_frame(const StrainField& field, const movie::Layout& layout,
                                     const Placement& placement, double gain_um_per_strain) {
  const auto n = deflection_direction(layout, placement);
  const bool along_x = layout.axis == movie::DeflectionAxis::x;
  // Lines run along the deflection axis: rows for axis x, columns for axis y.
  const std::int32_t lines = along_x ? layout.rows : layout.cols;
  const std::int32_t length = along_x ? layout.cols : layout.rows;
  const double pitch_mm = along_x ? layout.pitch_x_mm : layout.pitch_y_mm;
  const auto index = [&](std::int32_t line, std::int32_t k) {
    return static_cast<std::size_t>(along_x ? line * layout.cols + k : k * layout.cols + line);
  };

  const auto positions = contactor_positions_mm(layout, placement);
  std::vector<double> deflection_um(positions.size(), 0.0);
  if (length < 2) return deflection_um;
  Eigen::MatrixXd d(length - 1, length);
  Eigen::VectorXd g(length - 1);
  for (std::int32_t line = 0; line < lines; ++line) {
    Eigen::Index rows = 0;
    d.setZero();
    for (std::int32_t k = 0; k + 1 < length; ++k) {
      const auto& a = positions[index(line, k)];
      const auto& b = positions[index(line, k + 1)];
      const auto e = sample(field, (a.x_mm + b.x_mm) / 2, (a.y_mm + b.y_mm) / 2);
      if (!e) continue;  // no measurement between these two: leave the difference free
      d(rows, k) = -1.0;
      d(rows, k + 1) = 1.0;
      g(rows) = gain_um_per_strain * normal_strain(*e, n.x_mm, n.y_mm) * pitch_mm;
      ++rows;
    }
    if (rows == 0) continue;
    // Minimum-norm solution: its component along the null space (a constant per connected run of
    // contactors, any value on an isolated one) is zero, so runs come out zero-mean and isolated
    // contactors neutral without an explicit constraint.
    const Eigen::VectorXd solution =
        d.topRows(rows).completeOrthogonalDecomposition().solve(g.head(rows));
    for (std::int32_t k = 0; k < length; ++k) deflection_um[index(line, k)] = solution(k);
  }
  return deflection_um;
}

}  // namespace tactile::mapping
