// Strain tensors of single triangles and the sampled field of a whole frame.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "synthetic.hpp"
#include "tactile/mapping/strain_field.hpp"

namespace tactile::mapping {
namespace {

using capture::PointMm;

// Relative length changes of the triangle's edges (p0p1, p1p2, p2p0) under x -> F x.
std::array<double, 3> edge_changes(const std::array<PointMm, 3>& p,
                                   const std::array<double, 4>& f) {
  std::array<double, 3> change{};
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& a = p[i];
    const auto& b = p[(i + 1) % 3];
    const double dx = b.x_mm - a.x_mm;
    const double dy = b.y_mm - a.y_mm;
    const double fx = f[0] * dx + f[1] * dy;
    const double fy = f[2] * dx + f[3] * dy;
    change[i] = std::hypot(fx, fy) / std::hypot(dx, dy) - 1.0;
  }
  return change;
}

const std::array<PointMm, 3> kTriangle{{{1.0, 2.0}, {2.1, 2.2}, {1.4, 3.0}}};

TEST(TriangleStrain, RecoversAnExactTensorFromItsNormalStrains) {
  // rel_change given as n^T E n exactly: the solve must return E to rounding.
  const StrainTensor e{0.031, -0.012, 0.007};
  std::array<double, 3> change{};
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& a = kTriangle[i];
    const auto& b = kTriangle[(i + 1) % 3];
    const double len = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
    const double nx = (b.x_mm - a.x_mm) / len;
    const double ny = (b.y_mm - a.y_mm) / len;
    change[i] = e.exx * nx * nx + e.eyy * ny * ny + 2 * e.exy * nx * ny;
  }
  const auto got = triangle_strain(kTriangle, change, 0.1);
  ASSERT_TRUE(got);
  EXPECT_NEAR(got->exx, e.exx, 1e-12);
  EXPECT_NEAR(got->eyy, e.eyy, 1e-12);
  EXPECT_NEAR(got->exy, e.exy, 1e-12);
}

TEST(TriangleStrain, UniformStretchGivesTheStretches) {
  const double a = 0.02;
  const double b = -0.015;
  const auto got = triangle_strain(kTriangle, edge_changes(kTriangle, {1 + a, 0, 0, 1 + b}), 0.1);
  ASSERT_TRUE(got);
  // Small-strain recovery is exact to first order; the residual is O(strain^2).
  const double tol = 2 * a * a;
  EXPECT_NEAR(got->exx, a, tol);
  EXPECT_NEAR(got->eyy, b, tol);
  EXPECT_NEAR(got->exy, 0.0, tol);
}

TEST(TriangleStrain, SimpleShearGivesHalfTheShearAngle) {
  // x' = x + g y: small-strain tensor [[0, g/2], [g/2, 0]].
  const double g = 0.03;
  const auto got = triangle_strain(kTriangle, edge_changes(kTriangle, {1, g, 0, 1}), 0.1);
  ASSERT_TRUE(got);
  const double tol = 2 * g * g;
  EXPECT_NEAR(got->exx, 0.0, tol);
  EXPECT_NEAR(got->eyy, 0.0, tol);
  EXPECT_NEAR(got->exy, g / 2, tol);
}

TEST(TriangleStrain, RigidRotationGivesNoStrain) {
  const double th = 0.4;  // large on purpose: lengths do not change at all
  const auto got = triangle_strain(
      kTriangle, edge_changes(kTriangle, {std::cos(th), -std::sin(th), std::sin(th), std::cos(th)}),
      0.1);
  ASSERT_TRUE(got);
  EXPECT_NEAR(got->exx, 0.0, 1e-12);
  EXPECT_NEAR(got->eyy, 0.0, 1e-12);
  EXPECT_NEAR(got->exy, 0.0, 1e-12);
}

TEST(TriangleStrain, RejectsDegenerateTriangles) {
  const std::array<PointMm, 3> flat{{{0, 0}, {1, 1}, {2, 2}}};
  EXPECT_FALSE(triangle_strain(flat, {0.01, 0.01, 0.01}, 0.0));
  const std::array<PointMm, 3> coincident{{{1, 1}, {1, 1}, {2, 0}}};
  EXPECT_FALSE(triangle_strain(coincident, {0.01, 0.01, 0.01}, 0.0));
  const std::array<PointMm, 3> sliver{{{0, 0}, {1, 0}, {0.5, 0.01}}};
  EXPECT_LT(triangle_quality(sliver), 0.1);
  EXPECT_FALSE(triangle_strain(sliver, {0.01, 0.01, 0.01}, 0.1));
  EXPECT_TRUE(triangle_strain(sliver, {0.01, 0.01, 0.01}, 0.0));
  const std::array<PointMm, 3> equilateral{{{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}}};
  EXPECT_NEAR(triangle_quality(equilateral), 1.0, 1e-12);
}

TEST(TriangleStrain, NormalStrainRotatesTheTensor) {
  const StrainTensor e{0.02, -0.01, 0.005};
  EXPECT_DOUBLE_EQ(normal_strain(e, 1, 0), 0.02);
  EXPECT_DOUBLE_EQ(normal_strain(e, 0, 1), -0.01);
  const double c = std::numbers::sqrt2 / 2;
  EXPECT_NEAR(normal_strain(e, c, c), (0.02 - 0.01) / 2 + 0.005, 1e-15);
}

TEST(StrainField, SamplesInsideAndMasksOutside) {
  testing::GridSpec grid{.width_mm = 6, .height_mm = 4, .spacing_mm = 0.5, .jitter_fraction = 0.2};
  const double a = 0.01;
  const auto frame = testing::make_frame(
      grid,
      [&](double x, double, double) {
        return PointMm{a * x, 0.0};
      },
      0.1, 0, 1);
  const auto field = build_strain_field(frame);
  EXPECT_EQ(field.triangles.size() + static_cast<std::size_t>(field.rejected_triangle_count),
            frame.triangles.size());
  EXPECT_DOUBLE_EQ(field.t_s, 0.1);
  for (double y = 0.7; y < 3.3; y += 0.37) {
    for (double x = 0.7; x < 5.3; x += 0.41) {
      const auto e = sample(field, x, y);
      ASSERT_TRUE(e) << x << ", " << y;
      EXPECT_NEAR(e->exx, a, 2 * a * a);
      EXPECT_NEAR(e->eyy, 0.0, 2 * a * a);
    }
  }
  EXPECT_FALSE(sample(field, -1.0, 2.0));
  EXPECT_FALSE(sample(field, 3.0, 4.8));
  EXPECT_FALSE(sample(field, 7.0, 2.0));
  EXPECT_FALSE(sample(field, std::nan(""), 2.0));
}

TEST(StrainField, PiecewiseConstantValueIsThatOfTheContainingTriangle) {
  // Two triangles of a unit square with different strains: each half answers its own tensor.
  capture::StrainFrame frame;
  frame.points_from = {{0, 0, {}, 0, 0, 0, 0},
                       {1, 0, {}, 0, 0, 1, 0},
                       {2, 0, {}, 0, 0, 1, 1},
                       {3, 0, {}, 0, 0, 0, 1}};
  frame.triangles = {{{0, 1, 2}}, {{0, 2, 3}}};
  // Bottom edge stretched by 2 %, everything else unchanged.
  frame.edges = {
      {0, 1, 1, 1.02, 0.02}, {1, 2, 1, 1, 0}, {0, 2, 1, 1, 0}, {2, 3, 1, 1, 0}, {0, 3, 1, 1, 0}};
  const auto field = build_strain_field(frame);
  ASSERT_EQ(field.triangles.size(), 2u);
  const auto lower = sample(field, 0.7, 0.2);  // below the diagonal
  const auto upper = sample(field, 0.2, 0.7);
  ASSERT_TRUE(lower && upper);
  EXPECT_NEAR(lower->exx, 0.02, 1e-12);
  EXPECT_NEAR(upper->exx, 0.0, 1e-12);
  EXPECT_TRUE(sample(field, 0.5, 0.5));  // on the shared edge: either side, but not masked
  EXPECT_TRUE(sample(field, 0.0, 0.0));  // on a vertex
}

TEST(StrainField, FallsBackToPositionsForMissingEdgesAndRejectsBadIndices) {
  testing::GridSpec grid{.width_mm = 2, .height_mm = 2, .spacing_mm = 1};
  auto frame = testing::make_frame(
      grid,
      [](double, double y, double) {
        return PointMm{0.0, 0.03 * y};
      },
      0.0, 0, 1);
  frame.edges.clear();
  const auto field = build_strain_field(frame);
  EXPECT_EQ(field.triangles.size(), frame.triangles.size());
  const auto e = sample(field, 1.2, 0.6);
  ASSERT_TRUE(e);
  EXPECT_NEAR(e->eyy, 0.03, 2 * 0.03 * 0.03);

  frame.points_to.clear();
  EXPECT_EQ(build_strain_field(frame).triangles.size(), 0u);  // no way to know the lengths

  auto bad = testing::make_frame(
      grid, [](double, double, double) { return PointMm{}; }, 0.0, 0, 1);
  bad.triangles[0].point_index[1] = 99;
  EXPECT_THROW(build_strain_field(bad), std::invalid_argument);
  bad = testing::make_frame(
      grid, [](double, double, double) { return PointMm{}; }, 0.0, 0, 1);
  bad.points_to.pop_back();
  EXPECT_THROW(build_strain_field(bad), std::invalid_argument);
}

}  // namespace
}  // namespace tactile::mapping
