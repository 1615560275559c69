// Fidelity metrics on hand-built movies whose answers are known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "synthetic.hpp"
#include "tactile/mapping/fidelity.hpp"

namespace tactile::mapping {
namespace {

using testing::grid_layout;
using testing::GridSpec;

// Source: uniform stretch along x whose size grows with time, e(t_k) = 0.001 * k, k = 1..5.
capture::StrainMovie growing_uniform_stretch() {
  return testing::make_movie(
      GridSpec{.width_mm = 8, .height_mm = 4, .spacing_mm = 0.5},
      [](double x, double, double t) {
        return capture::PointMm{0.001 * std::round(t * 60) * x, 0};
      },
      5, 60.0);
}

// One 1 x 4 row at 2 mm pitch centred on the field, played at the camera rate: display frame k
// shows strain frame k. Each frame's neighbour differences are `scale * um_per_strain * pitch *
// e_k`, so the imposed strain is scale * e_k.
movie::TactileMovie row_movie(double scale, double um_per_strain) {
  movie::TactileMovie movie;
  movie.layout = grid_layout(1, 4, 2.0, 1.0);
  movie.layout.deflection_min_um = -1000;
  movie.layout.deflection_max_um = 1000;
  movie.rate_hz = 60;
  movie.frame_count = 5;
  for (int k = 1; k <= 5; ++k) {
    const double step = scale * um_per_strain * 2.0 * 0.001 * k;
    for (int c = 0; c < 4; ++c) movie.deflection_um.push_back(static_cast<float>(c * step));
  }
  return movie;
}

const Placement kCentre{4.0, 2.0, 0.0, 1.0};

TEST(Fidelity, ExactReproductionHasNoErrorAndFullCorrelation) {
  const auto m = fidelity(row_movie(1.0, 500), growing_uniform_stretch(), kCentre, 500, 1e9);
  EXPECT_EQ(m.compared_pairs, 5 * 3);
  EXPECT_NEAR(m.strain_rms_error, 0, 1e-6);
  EXPECT_NEAR(m.strain_correlation, 1, 1e-6);
  // RMS of 0.001 * k over k = 1..5 (three pairs each): sqrt(55 / 5) * 0.001.
  EXPECT_NEAR(m.source_strain_rms, std::sqrt(11.0) * 0.001, 1e-6);
}

TEST(Fidelity, DoubledStrainCorrelatesFullyButErrsByTheSourceItself) {
  const auto m = fidelity(row_movie(2.0, 500), growing_uniform_stretch(), kCentre, 500, 1e9);
  EXPECT_NEAR(m.strain_correlation, 1, 1e-6);
  EXPECT_NEAR(m.strain_rms_error, std::sqrt(11.0) * 0.001, 1e-6);
}

TEST(Fidelity, SaturationSlewAndSmoothnessCountExactly) {
  movie::TactileMovie movie;
  movie.layout = grid_layout(1, 2, 1.0, 1.0);  // range [-50, 50]
  movie.rate_hz = 100;
  movie.frame_count = 4;
  // Contactor 0 parabola d = 5 k^2 (second difference 10 um per frame^2); contactor 1 at the top
  // limit in frames 1 and 3, at the bottom in frame 2.
  movie.deflection_um = {0, 0, 5, 50, 20, -50, 45, 50};
  const auto m = fidelity(movie, growing_uniform_stretch(), kCentre, 1000, 5000);  // 50 um/frame
  EXPECT_DOUBLE_EQ(m.saturated_fraction, 3.0 / 8.0);
  // Steps of contactor 1: 50, -100, 100 (>= 50 um/frame: all three); contactor 0: 5, 15, 25.
  EXPECT_DOUBLE_EQ(m.slew_limited_fraction, 3.0 / 6.0);
  // Second differences: contactor 0: 10, 10; contactor 1: -150, 200 (per frame^2, x 100^2).
  const double want = std::sqrt((100.0 + 100 + 22500 + 40000) / 4) * 1e4;
  EXPECT_NEAR(m.rms_acceleration_um_per_s2, want, 1e-6 * want);
  EXPECT_NEAR(m.rms_deflection_um, std::sqrt((0.0 + 0 + 25 + 2500 + 400 + 2500 + 2025 + 2500) / 8),
              1e-4);
}

TEST(Fidelity, MaskedPairsAreLeftOutAndBadScaleRefused) {
  Placement far = kCentre;
  far.centre_x_mm = 100;  // the whole row off the measured field
  const auto m = fidelity(row_movie(1.0, 500), growing_uniform_stretch(), far, 500, 1e9);
  EXPECT_EQ(m.compared_pairs, 0);
  EXPECT_EQ(m.strain_correlation, 0);
  EXPECT_THROW(fidelity(row_movie(1.0, 500), growing_uniform_stretch(), kCentre, 0, 1e9),
               std::invalid_argument);
}

}  // namespace
}  // namespace tactile::mapping
