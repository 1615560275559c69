// The feature plates and the simulated fingertip: geometry from the paper, and responses whose
// direction follows from the physics (a bump displaces more fluid than a pit, contact starts
// when the press ramp starts).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "tactile/perception/sensor_model.hpp"

namespace perception = tactile::perception;

TEST(SensorScene, PaperFeaturePlates) {
  const auto f = perception::paper_features();
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
  const perception::SurfaceFeature cone{perception::Curvature::conical, 10, 2.5};
  EXPECT_NEAR(cone.surface_mm(2.5), 1.25, 1e-12);  // halfway out, half height
  // Hemisphere: footprint 5, height 2.5: z = sqrt(2.5^2 - r^2).
  const perception::SurfaceFeature sphere{perception::Curvature::spherical, 5, -2.5};
  EXPECT_NEAR(sphere.surface_mm(1.5), -2.0, 1e-12);
  EXPECT_DOUBLE_EQ(perception::paper_kinematics(perception::Procedure::roll).contact_angle_deg, 30);
  EXPECT_DOUBLE_EQ(
      perception::paper_kinematics(perception::Procedure::radial_ulnar).contact_angle_deg, 25);
}

TEST(SensorModel, LayoutRatesAndBaseline) {
  const perception::SurfaceFeature f{perception::Curvature::spherical, 10, 2.5};
  const auto r = perception::simulate_trial(f, perception::Procedure::static_contact, 7);
  const auto k = perception::paper_kinematics(perception::Procedure::static_contact);
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
  for (auto c : {perception::Curvature::planar, perception::Curvature::conical,
                 perception::Curvature::spherical}) {
    const auto bump =
        perception::simulate_trial({c, 7.5, 2.5}, perception::Procedure::static_contact, 3);
    const auto pit =
        perception::simulate_trial({c, 7.5, -2.5}, perception::Procedure::static_contact, 3);
    const std::size_t mid = bump.rows() / 2;
    // The electrodes over the feature (centre column E18/E19) see the skin pushed in by a bump
    // and let out over a pit.
    EXPECT_GT(bump.electrodes[17][mid] - bump.electrodes[17][0],
              pit.electrodes[17][mid] - pit.electrodes[17][0] + 20);
  }
}

TEST(SensorModel, TrialsVaryButAreReproducible) {
  const perception::SurfaceFeature f{perception::Curvature::conical, 5, 2.5};
  const auto a = perception::simulate_trial(f, perception::Procedure::distal_proximal, 11);
  const auto b = perception::simulate_trial(f, perception::Procedure::distal_proximal, 11);
  const auto c = perception::simulate_trial(f, perception::Procedure::distal_proximal, 12);
  EXPECT_EQ(a.pressure, b.pressure);
  EXPECT_NE(a.pressure, c.pressure);
}

// The spreads documented in docs/perception-models.md ("Trial-to-trial variation"): position and
// angle within the arm's measured repeatability (x5-x20), depth N(1, 0.03), speed N(1, 0.005).
TEST(SensorModel, TrialVariationHasTheDocumentedSpread) {
  constexpr int n = 4000;
  double depth_sum = 0, depth_sq = 0, speed_sum = 0, speed_sq = 0;
  for (int s = 0; s < n; ++s) {
    const auto v = perception::draw_variation(static_cast<std::uint64_t>(s));
    EXPECT_LE(std::abs(v.offset_x_mm), 0.1);
    EXPECT_LE(std::abs(v.offset_y_mm), 0.1);
    EXPECT_LE(std::abs(v.angle_deg), 0.1);
    depth_sum += v.depth_scale;
    depth_sq += v.depth_scale * v.depth_scale;
    speed_sum += v.speed_scale;
    speed_sq += v.speed_scale * v.speed_scale;
  }
  const auto sd = [&](double sum, double sq) {
    return std::sqrt(std::max(0.0, sq / n - (sum / n) * (sum / n)));
  };
  // Sample standard deviations of 4000 draws are within ~2 % of the true one (1 / sqrt(2n)).
  EXPECT_NEAR(sd(depth_sum, depth_sq), 0.03, 0.03 * 0.1);
  EXPECT_NEAR(sd(speed_sum, speed_sq), 0.005, 0.005 * 0.1);
  EXPECT_NEAR(depth_sum / n, 1.0, 0.003);
  // No variation at scale 0.
  const auto z = perception::draw_variation(9, {0, 0, 0});
  EXPECT_EQ(z.offset_x_mm, 0.0);
  EXPECT_EQ(z.depth_scale, 1.0);
}

// Each part of the variation scales on its own: position (and angle), depth, speed.
TEST(SensorModel, TrialVariationScalesEachPartAlone) {
  for (std::uint64_t s = 1; s < 50; ++s) {
    const auto full = perception::draw_variation(s);
    const auto position = perception::draw_variation(s, {0.25, 1, 1});
    EXPECT_DOUBLE_EQ(position.offset_x_mm, 0.25 * full.offset_x_mm);
    EXPECT_DOUBLE_EQ(position.offset_y_mm, 0.25 * full.offset_y_mm);
    EXPECT_DOUBLE_EQ(position.angle_deg, 0.25 * full.angle_deg);
    EXPECT_EQ(position.depth_scale, full.depth_scale);
    EXPECT_EQ(position.speed_scale, full.speed_scale);
    const auto depth = perception::draw_variation(s, {1, 2, 0});
    EXPECT_NEAR(depth.depth_scale - 1, 2 * (full.depth_scale - 1), 1e-12);
    EXPECT_EQ(depth.speed_scale, 1.0);
    EXPECT_EQ(depth.offset_x_mm, full.offset_x_mm);
  }
}

// Electrode noise in free air matches the real recordings (second differences of ele1..ele19 at
// rest in tests/data/biotac-slide: 0.6-1.0 counts), which are integer counts.
TEST(SensorModel, ElectrodeNoiseInFreeAirIsAboutOneCount) {
  const auto r = perception::simulate_trial({perception::Curvature::planar, 5, 2.5},
                                            perception::Procedure::static_contact, 21);
  const auto rest = static_cast<std::size_t>(
      perception::paper_kinematics(perception::Procedure::static_contact).rest_s * r.rate_hz - 2);
  double sq = 0;
  std::size_t count = 0;
  for (const auto& e : r.electrodes)
    for (std::size_t i = 1; i + 1 < rest; ++i) {
      EXPECT_EQ(e[i], std::round(e[i]));
      const double d2 = e[i + 1] - 2 * e[i] + e[i - 1];  // variance 6 sigma^2 for white noise
      sq += d2 * d2;
      ++count;
    }
  const double sigma = std::sqrt(sq / static_cast<double>(count) / 6);
  EXPECT_GT(sigma, 0.5);
  EXPECT_LT(sigma, 1.2);
}

// A 1.25 mm bump pressed statically between the two centre electrodes 1.5 mm on either side of
// it, with only the position spread (+-0.1 mm) varying from trial to trial. Its response on
// those electrodes (the trial minus the same trial on a bare plate: same seed, same noise) must
// be steady with the sheet field, whose weight falls as 1 / r^2 (relative slope 2 / r = 1.3 per
// mm there), and is erratic with the Gaussian one, whose flank falls as exp(-r^2 / 2 sigma^2)
// (relative slope r / sigma^2 = 9 per mm, and the feature's edge terms change sign across it).
TEST(SensorModel, SheetFieldSeesASmallFeatureSmoothlyInItsPosition) {
  const perception::SurfaceFeature bump{perception::Curvature::planar, 1.25, 0.625};
  const perception::SurfaceFeature bare{perception::Curvature::planar, 1.25, 0.0};
  const auto spread = [&](perception::ElectrodeField field, double& mean_counts) {
    perception::SensorModel m;
    m.electrode_field = field;
    m.variation = {1, 0, 0};
    double sum = 0, sum2 = 0;
    int n = 0;
    for (std::uint64_t seed = 1; seed <= 12; ++seed) {
      const auto a =
          perception::simulate_trial(bump, perception::Procedure::static_contact, seed, m);
      const auto b =
          perception::simulate_trial(bare, perception::Procedure::static_contact, seed, m);
      const std::size_t lo = a.rows() * 2 / 5, hi = a.rows() * 3 / 5;
      for (int e : {17, 18}) {  // the centre column's electrodes at x = -1.5 and +1.5 mm
        double d = 0;
        for (std::size_t i = lo; i < hi; ++i) d += a.electrodes[e][i] - b.electrodes[e][i];
        d /= static_cast<double>(hi - lo);
        sum += d;
        sum2 += d * d;
        ++n;
      }
    }
    mean_counts = sum / n;
    return std::sqrt(std::max(0.0, sum2 / n - mean_counts * mean_counts)) / std::abs(mean_counts);
  };
  double sheet_mean = 0, gaussian_mean = 0;
  const double sheet = spread(perception::ElectrodeField::sheet, sheet_mean);
  const double gaussian = spread(perception::ElectrodeField::gaussian, gaussian_mean);
  EXPECT_GT(sheet_mean, 100.0);  // the bump is seen 1.5 mm away
  EXPECT_LT(sheet, 0.25) << sheet_mean;
  EXPECT_LT(sheet * 4, gaussian) << sheet << " " << gaussian << " " << gaussian_mean;
}

TEST(SensorModel, SheetFieldRefusesImpossibleSizes) {
  const perception::SurfaceFeature bump{perception::Curvature::planar, 5, 2.5};
  for (const auto& [face, reach] : {std::pair{0.0, 3.0}, {-1.0, 3.0}, {0.5, 0.8}, {0.5, 100.0}}) {
    perception::SensorModel m;
    m.electrode_field = perception::ElectrodeField::sheet;
    m.sheet_face_mm = face;
    m.sheet_reach_mm = reach;
    EXPECT_THAT(
        [&] { perception::simulate_trial(bump, perception::Procedure::static_contact, 1, m); },
        ::testing::ThrowsMessage<std::invalid_argument>(
            ::testing::HasSubstr("sheet electrode field")))
        << face << " " << reach;
  }
}

TEST(SensorModel, VibrationRingsWhereAStrokeMeetsAnEdgeNotInAStaticPress) {
  // Without friction noise or sensor noise, a trial's vibration with the skin's ringing minus the
  // same trial's without it is the ringing alone. A distal-proximal stroke over a 20 mm planar
  // bump meets its 2.5 mm edges, whose tented skin changes slope by sqrt(2 h / rho) = 7.1 at the
  // foot: a kick of 7.1 x edge_gain, which a Q = 3 resonator rings to at most twice that (less as
  // the kink is crossed over a few samples). A static press meets no edge.
  perception::SensorModel quiet;
  quiet.friction_noise_per_unit = 0;
  quiet.vibration_noise = 0;
  perception::SensorModel silent = quiet;
  silent.edge_gain = 0;
  const perception::SurfaceFeature bump{perception::Curvature::planar, 20, 2.5};
  const auto ringing = [&](perception::Procedure p) {
    const auto with = perception::simulate_trial(bump, p, 1, quiet);
    const auto without = perception::simulate_trial(bump, p, 1, silent);
    double peak = 0;
    for (std::size_t i = 0; i < with.vibration.size(); ++i)
      peak = std::max(peak, std::abs(with.vibration[i] - without.vibration[i]));
    return peak;
  };
  const double stroke = ringing(perception::Procedure::distal_proximal);
  EXPECT_GT(stroke, 1.2 * 7.1 * quiet.edge_gain);
  EXPECT_LT(stroke, 2.0 * 7.1 * quiet.edge_gain + 1);  // + rounding to counts
  EXPECT_EQ(ringing(perception::Procedure::static_contact), 0.0);
}
