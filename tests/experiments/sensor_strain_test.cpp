// Skin strain of the simulated fingertip against hand-computed cases on a flat plate (the pad's
// indentation at the arm's balance is then known in closed form).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tactile/experiments/sensor_strain.hpp"

namespace tactile::experiments {
namespace {

using namespace tactile::capture;
using namespace tactile::perception;

// A planar feature of height 0 is the flat plate; no trial-to-trial variation. (The model counts
// the fluid layer's saturation only inside a feature's footprint; with the smallest footprint that
// moves the balance by about 1 um, which the 0.5 % tolerances below allow for.)
const SurfaceFeature kFlat{Curvature::planar, 1.25, 0.0};

SensorModel still_model() {
  SensorModel m;
  m.variation = {0, 0, 0};
  return m;
}

// The Winkler skin on the flat plate at the balance: the arm's spring is set so that the pad
// takes 30 % of the commanded 5.5 mm, u = 3 tanh((1.65 - x^2 / 30 - y^2 / 16) / 3).
double flat_u(double x, double y) {
  const double free = 1.65 - x * x / 30 - y * y / 16;
  return free <= 0 ? 0.0 : 3 * std::tanh(free / 3);
}

const StrainEdge& edge_between(const StrainFrame& f, std::int32_t a, std::int32_t b) {
  for (const auto& e : f.edges)
    if ((e.track_a == a && e.track_b == b) || (e.track_a == b && e.track_b == a)) return e;
  throw std::runtime_error("no such edge");
}

TEST(SkinStrain, GridFramesAndFreeAir) {
  SkinStrainOptions o;  // 21 x 15 nodes at 1 mm over 20 x 14 mm
  const auto movie = simulate_skin_strain(kFlat, Procedure::static_contact, 1, still_model(), o);
  // Static contact lasts 2 x 0.5 + 2 x 0.3 + 1.5 = 3.1 s: 310 frames, 309 strain frames.
  ASSERT_EQ(movie.frames.size(), 309u);
  EXPECT_DOUBLE_EQ(movie.frame_rate_hz, 100.0);
  EXPECT_DOUBLE_EQ(movie.field_width_mm, 20.0);
  EXPECT_DOUBLE_EQ(movie.field_height_mm, 14.0);
  const auto& first = movie.frames.front();
  EXPECT_EQ(first.points_from.size(), 21u * 15u);
  // Edges: 20 x 15 along x, 21 x 14 along y, 20 x 14 diagonals; two triangles per cell.
  EXPECT_EQ(first.edges.size(), 20u * 15 + 21u * 14 + 20u * 14);
  EXPECT_EQ(first.triangles.size(), 2u * 20 * 14);
  // Node 0 is the pad's proximal-radial corner (-10, -7) mm: field position (0, 0).
  EXPECT_DOUBLE_EQ(first.points_from[0].x_mm, 0.0);
  EXPECT_DOUBLE_EQ(first.points_from[0].y_mm, 0.0);
  // Free air (the first 0.5 s): the skin does not move.
  for (const auto& e : first.edges) EXPECT_EQ(e.rel_change, 0.0);
}

TEST(SkinStrain, StretchOfTheIndentedSkinFromRest) {
  SkinStrainOptions o;
  o.from_rest = true;
  const auto movie = simulate_skin_strain(kFlat, Procedure::static_contact, 1, still_model(), o);
  // Middle of the hold: t = 0.5 + 0.3 + 0.75 s = frame 155, strain frame 154 (frame_to 155).
  const auto& f = movie.frames[154];
  EXPECT_EQ(f.frame_from, 0);
  EXPECT_EQ(f.frame_to, 155);
  // Node (i, j) is x = -10 + i, y = -7 + j: the edge from the pad's centre (10, 7) one mm
  // distally, and one 3 mm further out where the slope is steeper.
  const auto id = [](int i, int j) { return j * 21 + i; };
  for (int x : {0, 3}) {
    const double du = flat_u(x + 1, 0) - flat_u(x, 0);
    const double expected = std::sqrt(1 + du * du) - 1;
    EXPECT_NEAR(edge_between(f, id(10 + x, 7), id(11 + x, 7)).rel_change, expected, 5e-3 * expected)
        << x;
  }
  // Across the finger (y) the pad is more curved: the edge at y = 2..3 mm.
  const double du = flat_u(0, 3) - flat_u(0, 2);
  const double across = std::sqrt(1 + du * du) - 1;
  EXPECT_NEAR(edge_between(f, id(10, 9), id(10, 10)).rel_change, across, 5e-3 * across);
  // Outside the contact (x = -10 mm: the pad is 3.3 mm above the plate) nothing stretches.
  EXPECT_EQ(edge_between(f, id(0, 7), id(1, 7)).rel_change, 0.0);
}

TEST(SkinStrain, SlidingDragsTheSkinByItsIndentation) {
  SkinStrainOptions o;
  o.from_rest = true;
  const auto movie = simulate_skin_strain(kFlat, Procedure::distal_proximal, 1, still_model(), o);
  // Mid-stroke (0.5 + 0.3 + 1.5 s = frame 230): the plate has slid 15 mm, the drag is built up.
  const auto& f = movie.frames[229];
  ASSERT_EQ(f.frame_to, 230);
  const auto centre = static_cast<std::size_t>(7 * 21 + 10);
  EXPECT_NEAR(f.points_to[centre].x_mm - f.points_from[centre].x_mm, 0.3 * flat_u(0, 0), 1e-3);
  EXPECT_NEAR(f.points_to[centre].y_mm, f.points_from[centre].y_mm, 1e-12);
  // A radial-ulnar stroke drags across the finger instead.
  const auto across =
      simulate_skin_strain(kFlat, Procedure::radial_ulnar, 1, still_model(), o).frames[229];
  EXPECT_NEAR(across.points_to[centre].y_mm - across.points_from[centre].y_mm, 0.3 * flat_u(0, 0),
              1e-3);
}

TEST(SkinStrain, BadGridsAreRefused) {
  SkinStrainOptions o;
  o.grid_spacing_mm = 0;
  EXPECT_THROW(simulate_skin_strain(kFlat, Procedure::roll, 1, {}, o), std::invalid_argument);
  o.grid_spacing_mm = 1;
  o.half_width_mm = std::nan("");
  EXPECT_THROW(simulate_skin_strain(kFlat, Procedure::roll, 1, {}, o), std::invalid_argument);
}

}  // namespace
}  // namespace tactile::experiments
