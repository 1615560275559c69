// The feature plates and the simulated fingertip: geometry from the paper, and responses whose
// direction follows from the physics (a bump displaces more fluid than a pit, contact starts
// when the press ramp starts).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tactile/capture/sensor_model.hpp"

namespace cap = tactile::capture;

TEST(SensorScene, PaperFeaturePlates) {
  const auto f = cap::paper_features();
  ASSERT_EQ(f.size(), 48u);
  int bumps = 0;
  for (const auto& x : f) {
    bumps += x.height_mm > 0;
    const double expected_h = x.footprint_mm <= 3.75 ? x.footprint_mm / 2 : 2.5;
    EXPECT_DOUBLE_EQ(std::abs(x.height_mm), expected_h);
    // Centre at full height, edge at the plate.
    EXPECT_NEAR(x.surface_mm(0.0), x.height_mm, 1e-12);
    EXPECT_EQ(x.surface_mm(x.footprint_mm / 2 + 1e-9), 0.0);
  }
  EXPECT_EQ(bumps, 24);
  const cap::SurfaceFeature cone{cap::Curvature::conical, 10, 2.5};
  EXPECT_NEAR(cone.surface_mm(2.5), 1.25, 1e-12);  // halfway out, half height
  // Hemisphere: footprint 5, height 2.5: z = sqrt(2.5^2 - r^2).
  const cap::SurfaceFeature sphere{cap::Curvature::spherical, 5, -2.5};
  EXPECT_NEAR(sphere.surface_mm(1.5), -2.0, 1e-12);
  EXPECT_DOUBLE_EQ(cap::paper_kinematics(cap::Procedure::roll).contact_angle_deg, 30);
  EXPECT_DOUBLE_EQ(cap::paper_kinematics(cap::Procedure::radial_ulnar).contact_angle_deg, 25);
}

TEST(SensorModel, LayoutRatesAndBaseline) {
  const cap::SurfaceFeature f{cap::Curvature::spherical, 10, 2.5};
  const auto r = cap::simulate_trial(f, cap::Procedure::static_contact, 7);
  const auto k = cap::paper_kinematics(cap::Procedure::static_contact);
  const double expected_s = 2 * k.rest_s + 2 * k.approach_s + k.hold_s;
  EXPECT_NEAR(static_cast<double>(r.rows()) / r.rate_hz, expected_s, 0.011);
  EXPECT_EQ(r.vibration.size(), 22 * r.rows());
  // Free air before the press: pressure within noise of its baseline.
  const auto rest_rows = static_cast<std::size_t>(k.rest_s * r.rate_hz) - 2;
  const auto [lo, hi] = std::minmax_element(r.pressure.begin(), r.pressure.begin() + rest_rows);
  EXPECT_LT(*hi - *lo, 6.0);
  EXPECT_GT(r.pressure[r.rows() / 2] - r.pressure[0], 50.0);
}

TEST(SensorModel, BumpPressesHarderThanPitInStaticContact) {
  for (auto c : {cap::Curvature::planar, cap::Curvature::conical, cap::Curvature::spherical}) {
    const auto bump = cap::simulate_trial({c, 7.5, 2.5}, cap::Procedure::static_contact, 3);
    const auto pit = cap::simulate_trial({c, 7.5, -2.5}, cap::Procedure::static_contact, 3);
    const std::size_t mid = bump.rows() / 2;
    // The electrodes over the feature (centre column E18/E19) see the skin pushed in by a bump
    // and let out over a pit.
    EXPECT_GT(bump.electrodes[17][mid] - bump.electrodes[17][0],
              pit.electrodes[17][mid] - pit.electrodes[17][0] + 20);
  }
}

TEST(SensorModel, TrialsVaryButAreReproducible) {
  const cap::SurfaceFeature f{cap::Curvature::conical, 5, 2.5};
  const auto a = cap::simulate_trial(f, cap::Procedure::distal_proximal, 11);
  const auto b = cap::simulate_trial(f, cap::Procedure::distal_proximal, 11);
  const auto c = cap::simulate_trial(f, cap::Procedure::distal_proximal, 12);
  EXPECT_EQ(a.pressure, b.pressure);
  EXPECT_NE(a.pressure, c.pressure);
  const auto v = cap::draw_variation(5);
  EXPECT_LE(std::abs(v.offset_x_mm), 0.5);
  EXPECT_LE(std::abs(v.angle_deg), 1.0);
}
