// Method "profile": deflection against the slope of a Gaussian surface under the moving finger,
// checked against the closed-form derivative of the Gaussian.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "synthetic.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/error.hpp"
#include "tactile/mapping/map.hpp"
#include "tactile/mapping/profile.hpp"

namespace tactile::mapping {
namespace {

using ::testing::HasSubstr;

// A bump of height A and FWHM w has sigma = w / (2 sqrt(2 ln 2)); its slope along x at distance
// u from the centre (on the centre line) is -A u / sigma^2 exp(-u^2 / (2 sigma^2)).
double slope(double a_mm, double w_mm, double u_mm) {
  const double s = w_mm / (2 * std::sqrt(2 * std::log(2.0)));
  return -a_mm * u_mm / (s * s) * std::exp(-u_mm * u_mm / (2 * s * s));
}

SurfaceProfile bump_at_origin() {
  SurfaceProfile p;
  p.shape = ProfileShape::bump;
  p.height_mm = 0.5;
  p.width_mm = 3.0;
  p.finger_x0_mm = -4.0;  // grid centre 4 mm before the bump, moving at 2 mm/s along +x
  p.velocity_x_mm_per_s = 2.0;
  return p;
}

TEST(Profile, DeflectsAgainstTheSlopeUnderEachContactorAsTheFingerMoves) {
  const auto layout = testing::grid_layout(1, 3, 1.0, 1.0);
  for (const double t : {0.0, 0.75, 2.0, 3.1}) {
    const auto d = profile_frame(bump_at_origin(), layout, t, 100.0);
    ASSERT_EQ(d.size(), 3u);
    for (int c = 0; c < 3; ++c) {
      const double x = -4.0 + 2.0 * t + (c - 1) * 1.0;  // contactor c over the surface
      EXPECT_NEAR(d[static_cast<std::size_t>(c)], -100.0 * slope(0.5, 3.0, x), 1e-9)
          << "t " << t << " contactor " << c;
    }
  }
  // At t = 2 s the middle contactor is on top of the bump: no slope, no deflection; its
  // neighbours are on opposite slopes and deflect oppositely.
  const auto top = profile_frame(bump_at_origin(), layout, 2.0, 100.0);
  EXPECT_NEAR(top[1], 0, 1e-12);
  EXPECT_NEAR(top[0], -top[2], 1e-12);
  // Before the top the surface rises: the skin is pushed back, against the motion (-x).
  EXPECT_LT(top[0], 0);
}

TEST(Profile, HoleIsTheNegativeOfTheBumpAndFlatIsStill) {
  const auto layout = testing::grid_layout(2, 2, 1.0, 1.0);
  auto hole = bump_at_origin();
  hole.shape = ProfileShape::hole;
  auto flat = bump_at_origin();
  flat.shape = ProfileShape::flat;
  const auto b = profile_frame(bump_at_origin(), layout, 1.3, 50.0);
  const auto h = profile_frame(hole, layout, 1.3, 50.0);
  const auto f = profile_frame(flat, layout, 1.3, 50.0);
  for (std::size_t i = 0; i < b.size(); ++i) {
    EXPECT_DOUBLE_EQ(h[i], -b[i]);
    EXPECT_EQ(f[i], 0.0);
  }
}

TEST(Profile, AxisYUsesTheSlopeAcrossTheSlide) {
  auto layout = testing::grid_layout(3, 1, 1.0, 1.5, movie::DeflectionAxis::y);
  auto p = bump_at_origin();
  p.finger_x0_mm = 0;  // centred on the bump: along y the contactors sit at -1.5, 0, 1.5
  const auto d = profile_frame(p, layout, 0.0, 100.0);
  EXPECT_NEAR(d[0], -100.0 * slope(0.5, 3.0, -1.5), 1e-9);
  EXPECT_NEAR(d[1], 0, 1e-12);
  EXPECT_NEAR(d[2], -100.0 * slope(0.5, 3.0, 1.5), 1e-9);
}

TEST(Profile, SceneProfileCentresTheFingerPathOnTheFeature) {
  capture::SceneSpec spec;  // 180 frames at 60 Hz, 2.4 mm/s
  const auto p = profile_of_scene(spec);
  EXPECT_EQ(p.shape, ProfileShape::bump);
  const double travel = 2.4 * 179 / 60.0;
  EXPECT_NEAR(p.finger_x0_mm + p.velocity_x_mm_per_s * 179 / 60.0 / 2, p.feature_x_mm, 1e-9);
  EXPECT_NEAR(p.feature_x_mm - p.finger_x0_mm, travel / 2, 1e-9);
  spec.scene = capture::Scene::flat_slide;
  EXPECT_EQ(profile_of_scene(spec).shape, ProfileShape::flat);
}

TEST(Profile, MappingUsesTheStrainFramesOnlyForTheirTimes) {
  const auto movie = testing::make_movie(
      testing::GridSpec{.width_mm = 4, .height_mm = 4, .spacing_mm = 1},
      [](double, double, double) {
        return capture::PointMm{0, 0};
      },
      30, 60.0);
  const auto layout = testing::grid_layout(1, 3, 1.0, 1.0);
  MappingParams params;
  params.method = MappingMethod::profile;
  params.rate_hz = 60;
  params.gain_um_per_strain = 40;
  params.slew_limit_um_per_s = 1e9;
  try {
    map_strain_movie(movie, layout, params);
    FAIL() << "profile without a surface was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("method 'profile' needs a surface profile"));
  }
  params.profile = bump_at_origin();
  const auto out = map_strain_movie(movie, layout, params);
  ASSERT_EQ(out.frame_count, 30);
  for (int f = 0; f < 30; ++f) {
    const double t = (f + 1) / 60.0;  // strain frame f ends at camera frame f + 1
    const auto want = profile_frame(*params.profile, layout, t, 40);
    for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(out.frame(f)[c], want[c], 1e-4);
  }
}

}  // namespace
}  // namespace tactile::mapping
