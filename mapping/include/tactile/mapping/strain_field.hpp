#pragma once
// The measured strain of one StrainFrame as a field that can be sampled anywhere in the camera's
// image plane (millimetres, the from-frame positions of the tracked landmarks).
//
// Each Delaunay triangle carries one 2-D small-strain tensor, recovered from the relative length
// changes of its three edges. Between landmarks the field is piecewise constant: a point takes the
// tensor of the triangle that contains it. Outside the triangulation (and inside rejected,
// degenerate triangles) the field is masked: sample() answers std::nullopt.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "tactile/capture/strain_movie.hpp"

namespace tactile::mapping {

// Symmetric 2-D small-strain tensor [[exx, exy], [exy, eyy]] (dimensionless; exy is the tensor
// shear component, half the engineering shear strain).
struct StrainTensor {
  double exx = 0;
  double eyy = 0;
  double exy = 0;
};

// Normal strain along the unit direction (nx, ny): n^T E n.
double normal_strain(const StrainTensor& strain, double nx, double ny);

struct StrainFieldOptions {
  // Triangles whose shape quality 4*sqrt(3)*area / (a^2 + b^2 + c^2) (1 = equilateral, 0 = flat)
  // is below this are rejected: the slivers Delaunay leaves along the convex hull turn a pixel of
  // tracking error into tens of percent of strain.
  double min_triangle_quality = 0.1;
};

// Strain tensor of a triangle with vertices p[0..2] (from-frame, mm) whose edges p0-p1, p1-p2 and
// p2-p0 changed length by rel_change[0..2] = (len_to - len_from) / len_from. Solves
// n_i^T E n_i = rel_change_i for the three edge directions n_i, which is exact to first order in
// the strain for a homogeneous deformation (rigid rotations give zero). Returns std::nullopt when
// the triangle's quality is below min_quality (degenerate directions make the solve ill-posed).
std::optional<StrainTensor> triangle_strain(const std::array<capture::PointMm, 3>& p,
                                            const std::array<double, 3>& rel_change,
                                            double min_quality);

// Shape quality used above: 4*sqrt(3)*area / (a^2 + b^2 + c^2), in [0, 1].
double triangle_quality(const std::array<capture::PointMm, 3>& p);

struct FieldTriangle {
  std::array<capture::PointMm, 3> vertex_mm;
  StrainTensor strain;
};

// Uniform grid of bins over the triangles' bounding box; each bin lists the triangles whose
// bounding boxes overlap it (compressed rows: bin b holds triangle_index[bin_start[b] ..
// bin_start[b + 1])).
struct TriangleBins {
  double x0_mm = 0;
  double y0_mm = 0;
  double bin_size_mm = 1;
  std::int32_t bins_x = 0;
  std::int32_t bins_y = 0;
  std::vector<std::int32_t> bin_start;
  std::vector<std::int32_t> triangle_index;
};

struct StrainField {
  double t_s = 0;                        // time of the StrainFrame's frame_to
  std::vector<FieldTriangle> triangles;  // the accepted triangles only
  std::int32_t rejected_triangle_count = 0;
  TriangleBins bins;
};

// Builds the field of one StrainFrame. Edge rel_change values come from frame.edges (matched by
// track ids); an edge missing there is measured from points_from/points_to instead, and a triangle
// with an edge known neither way is rejected. When `only_at` is not empty, only the triangles
// containing one of those points are solved and kept: the field is then right at those points
// (and masked elsewhere), which is all a mapping needs and several times cheaper than the whole
// triangulation. rejected_triangle_count counts among the triangles considered. Throws
// std::invalid_argument for triangle indices outside points_from or points_to not matching
// points_from.
StrainField build_strain_field(const capture::StrainFrame& frame,
                               const StrainFieldOptions& options = {},
                               std::span<const capture::PointMm> only_at = {});

// Whether (x, y) lies in the triangle (closed, with a relative tolerance of 1e-9 so that points on
// a shared edge belong to both neighbours).
bool triangle_contains(const std::array<capture::PointMm, 3>& vertex_mm, double x, double y);

// Calls visit(triangle index) for the triangles whose bounding boxes may hold (x_mm, y_mm), until
// visit returns true; nothing outside the bins.
template <typename Visit>
void for_each_candidate(const TriangleBins& bins, double x_mm, double y_mm, Visit&& visit) {
  if (bins.bins_x <= 0 || bins.bins_y <= 0 || !std::isfinite(x_mm) || !std::isfinite(y_mm)) {
    return;
  }
  const double fx = (x_mm - bins.x0_mm) / bins.bin_size_mm;
  const double fy = (y_mm - bins.y0_mm) / bins.bin_size_mm;
  // A point just past the last bin edge may still lie on the hull; the clamp below catches it,
  // and anything further out is outside every triangle's bounding box.
  constexpr double kSlack = 1e-6;
  if (fx < -kSlack || fy < -kSlack || fx > bins.bins_x + kSlack || fy > bins.bins_y + kSlack) {
    return;
  }
  const auto bx = std::min(static_cast<std::int32_t>(std::max(fx, 0.0)), bins.bins_x - 1);
  const auto by = std::min(static_cast<std::int32_t>(std::max(fy, 0.0)), bins.bins_y - 1);
  const auto b = static_cast<std::size_t>(by) * static_cast<std::size_t>(bins.bins_x) +
                 static_cast<std::size_t>(bx);
  for (auto i = bins.bin_start[b]; i < bins.bin_start[b + 1]; ++i) {
    if (visit(bins.triangle_index[static_cast<std::size_t>(i)])) return;
  }
}

// The strain at (x_mm, y_mm): the tensor of the containing triangle (piecewise constant), or
// std::nullopt outside the measured region. Points on a shared edge take either triangle's value.
std::optional<StrainTensor> sample(const StrainField& field, double x_mm, double y_mm);

}  // namespace tactile::mapping
