// The whole mapping on synthetic strain movies with analytic strain.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numbers>

#include "synthetic.hpp"
#include "tactile/mapping/map.hpp"

namespace tactile::mapping {
namespace {

using capture::PointMm;
using testing::grid_layout;
using testing::GridSpec;
using ::testing::HasSubstr;
using testing::proportional_params;

constexpr double kA = 0.01;   // uniform stretch along x
constexpr double kB = -0.02;  // uniform stretch along y

capture::StrainMovie uniform_movie(std::int32_t frames, double rate_hz = 60.0,
                                   double spacing_mm = 0.5) {
  return testing::make_movie(
      GridSpec{.spacing_mm = spacing_mm, .jitter_fraction = 0.2},
      [](double x, double y, double) {
        return PointMm{kA * x, kB * y};
      },
      frames, rate_hz);
}

// A Gaussian ridge of x-strain, exx = eps * exp(-(x - c)^2 / (2 sigma^2)), travelling along x
// at speed_mm_per_s from c = start_mm: the displacement is its integral (an erf).
struct MovingBump {
  double eps = 0.04;
  double sigma_mm = 1.0;
  double start_mm = -4.0;
  double speed_mm_per_s = 18.0;

  double centre_mm(double t_s) const { return start_mm + speed_mm_per_s * t_s; }
  double exx(double x_mm, double t_s) const {
    const double z = (x_mm - centre_mm(t_s)) / sigma_mm;
    return eps * std::exp(-z * z / 2);
  }
  PointMm displacement(double x_mm, double t_s) const {
    const double z = (x_mm - centre_mm(t_s)) / (sigma_mm * std::numbers::sqrt2);
    return {eps * sigma_mm * std::sqrt(std::numbers::pi / 2) * std::erf(z), 0.0};
  }
};

// 35 Hz camera: every camera frame time is also a 700 Hz display frame time (every 20th). The bump
// crosses the 10 mm field in the movie's second.
capture::StrainMovie bump_movie(const MovingBump& bump, double spacing_mm = 0.3) {
  return testing::make_movie(
      GridSpec{.spacing_mm = spacing_mm, .jitter_fraction = 0.15},
      [bump](double x, double, double t) { return bump.displacement(x, t); }, 35, 35.0);
}
constexpr std::int32_t kBumpDisplayFrames = 681;  // 34/35 s at 700 Hz
constexpr std::int32_t kDisplayFramesPerCameraFrame = 20;

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const auto n = static_cast<double>(a.size());
  double ma = 0, mb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) ma += a[i] / n, mb += b[i] / n;
  double sab = 0, saa = 0, sbb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return sab / std::sqrt(saa * sbb);
}

TEST(MapStrainMovie, ShapeRateDurationAndProvenance) {
  const auto movie = uniform_movie(10);  // strain frames at 1/60 .. 10/60 s
  const auto layout = grid_layout(8, 8, 1.0, 1.0);
  MappingParams params;
  params.program_version = "9.9.9-test";
  const auto out = map_strain_movie(movie, layout, params);
  // 9/60 s spanned at 700 Hz: 105 intervals, 106 frames.
  EXPECT_EQ(out.frame_count, 106);
  EXPECT_EQ(out.rate_hz, 700.0);
  EXPECT_EQ(out.deflection_um.size(), 106u * 64u);
  EXPECT_NEAR(out.duration_s(), 106.0 / 700.0, 1e-12);
  EXPECT_EQ(out.layout.rows, 8);
  EXPECT_EQ(out.layout.name, "test");
  EXPECT_EQ(out.provenance.method, "integrated");  // the default method
  // The strain movie's file is the caller's to name; the library knows no file.
  EXPECT_EQ(out.provenance.input, "");
  EXPECT_EQ(out.provenance.command_line, "");
  EXPECT_FALSE(out.provenance.created_utc.empty());
  EXPECT_EQ(out.provenance.program_version, "9.9.9-test");
  const auto& json = out.provenance.parameters_json;
  EXPECT_THAT(json, HasSubstr("\"method\":\"integrated\""));
  EXPECT_THAT(json, HasSubstr("\"gain_um_per_strain\":1000.0"));
  EXPECT_THAT(json, HasSubstr("\"centre_x_mm\":5.0"));
  EXPECT_THAT(json, HasSubstr("\"auto\":true"));

  params.program_version.clear();
  EXPECT_FALSE(map_strain_movie(movie, layout, params).provenance.program_version.empty());
}

TEST(MapStrainMovie, ProportionalFollowsTheStrainAlongTheDeflectionAxis) {
  const auto movie = uniform_movie(6);
  MappingParams params = proportional_params();  // gain 1000 um per unit strain
  const double tol_um = 1000 * 2 * kB * kB;      // small-strain linearisation error
  auto out = map_strain_movie(movie, grid_layout(8, 8, 1.0, 1.0), params);
  for (const float d : out.deflection_um) ASSERT_NEAR(d, 1000 * kA, tol_um);

  out = map_strain_movie(movie, grid_layout(8, 8, 1.0, 1.0, movie::DeflectionAxis::y), params);
  for (const float d : out.deflection_um) ASSERT_NEAR(d, 1000 * kB, tol_um);

  // The grid turned a quarter: the layout's x axis now lies along the field's y.
  params.placement =
      Placement{.centre_x_mm = 5, .centre_y_mm = 5, .rotation_rad = std::numbers::pi / 2};
  out = map_strain_movie(movie, grid_layout(8, 8, 1.0, 1.0), params);
  for (const float d : out.deflection_um) ASSERT_NEAR(d, 1000 * kB, tol_um);
}

TEST(MapStrainMovie, ContactorsOutsideTheMeasuredRegionStayNeutral) {
  const auto movie = uniform_movie(3);
  MappingParams params = proportional_params();
  params.placement = Placement{.centre_x_mm = 0.0, .centre_y_mm = 5.0};  // on the left edge
  const auto layout = grid_layout(4, 4, 1.0, 1.0);  // columns at x = -1.5, -0.5, 0.5, 1.5
  const auto out = map_strain_movie(movie, layout, params);
  for (std::int32_t r = 0; r < 4; ++r) {
    EXPECT_EQ(out.frame(2)[static_cast<std::size_t>(r * 4 + 0)], 0.0f);
    EXPECT_EQ(out.frame(2)[static_cast<std::size_t>(r * 4 + 1)], 0.0f);
    EXPECT_NEAR(out.frame(2)[static_cast<std::size_t>(r * 4 + 3)], 1000 * kA, 1.0);
  }
}

TEST(MapStrainMovie, ProportionalTracksAMovingStrainBump) {
  const MovingBump bump;
  const auto movie = bump_movie(bump);
  const auto layout = grid_layout(8, 8, 1.0, 1.0);
  const auto out = map_strain_movie(movie, layout, proportional_params());
  ASSERT_EQ(out.frame_count, kBumpDisplayFrames);

  std::vector<double> mapped, expected;
  double max_error_um = 0;
  std::vector<double> activity;  // RMS deflection per display frame
  for (std::int32_t f = 0; f < out.frame_count; ++f) {
    const auto frame = out.frame(f);
    double sum = 0;
    for (const float d : frame) sum += d * d;
    activity.push_back(std::sqrt(sum / static_cast<double>(frame.size())));
    if (f % kDisplayFramesPerCameraFrame != 0)
      continue;  // camera frame times only: there the analytic value is exact
    const double t_s = movie.frames[static_cast<std::size_t>(f / kDisplayFramesPerCameraFrame)].t_s;
    for (std::int32_t c = 0; c < 8; ++c) {
      const double x_mm = 5.0 - 3.5 + c;
      const double want = 1000 * bump.exx(x_mm, t_s);
      for (std::int32_t r = 0; r < 8; ++r) {
        const double got = frame[static_cast<std::size_t>(r * 8 + c)];
        mapped.push_back(got);
        expected.push_back(want);
        max_error_um = std::max(max_error_um, std::abs(got - want));
      }
    }
  }
  // Piecewise-constant triangles 0.25 mm across on a bump of 1 mm sigma: a few um at most.
  EXPECT_GT(correlation(mapped, expected), 0.98);
  std::cout << "[ result ] max |mapped - analytic| = " << max_error_um << " um\n";
  EXPECT_LT(max_error_um, 8.0);

  // The bump enters from the left, crosses the grid and leaves: activity rises and falls.
  const auto peak = std::max_element(activity.begin(), activity.end());
  EXPECT_GT(*peak, 10.0);
  EXPECT_LT(activity.front(), 0.05 * *peak);
  EXPECT_LT(activity.back(), 0.05 * *peak);
  // Each column of contactors peaks when the bump's centre passes over it.
  for (std::int32_t c = 0; c < 8; ++c) {
    std::int32_t best = 0;
    for (std::int32_t f = 1; f < out.frame_count; ++f) {
      if (out.frame(f)[static_cast<std::size_t>(c)] >
          out.frame(best)[static_cast<std::size_t>(c)]) {
        best = f;
      }
    }
    const double x_mm = 5.0 - 3.5 + c;
    const double passes_s = (x_mm - bump.start_mm) / bump.speed_mm_per_s;
    EXPECT_NEAR(movie.frames[0].t_s + best / 700.0, passes_s, 0.02) << "column " << c;
  }
}

TEST(MapStrainMovie, IntegratedReproducesTheExtensionBetweenContactors) {
  const auto layout = grid_layout(6, 8, 1.0, 1.0);
  MappingParams params;
  params.method = MappingMethod::integrated;
  // Uniform stretch: every row is the same zero-mean ramp of 1000 * kA * pitch per contactor.
  auto out = map_strain_movie(uniform_movie(4), layout, params);
  for (std::int32_t r = 0; r < 6; ++r) {
    for (std::int32_t c = 0; c < 8; ++c) {
      EXPECT_NEAR(out.frame(3)[static_cast<std::size_t>(r * 8 + c)], 1000 * kA * (c - 3.5), 0.1);
    }
  }
  // Along y, the ramp runs down the columns.
  out = map_strain_movie(uniform_movie(4), grid_layout(5, 8, 1.0, 1.2, movie::DeflectionAxis::y),
                         params);
  for (std::int32_t r = 0; r < 5; ++r) {
    EXPECT_NEAR(out.frame(3)[static_cast<std::size_t>(r * 8 + 5)], 1000 * kB * 1.2 * (r - 2), 0.2);
  }

  // A moving bump: neighbouring differences follow the strain between the two contactors.
  MovingBump bump;
  bump.eps = 0.02;  // its integral (50 um) then fits the +/-50 um range, zero-mean
  const auto movie = bump_movie(bump);
  out = map_strain_movie(movie, layout, params);
  std::vector<double> got, want;
  for (std::int32_t f = 0; f < out.frame_count; f += kDisplayFramesPerCameraFrame) {
    const double t_s = movie.frames[static_cast<std::size_t>(f / kDisplayFramesPerCameraFrame)].t_s;
    const auto frame = out.frame(f);
    for (std::int32_t r = 0; r < 6; ++r) {
      double mean = 0;
      for (std::int32_t c = 0; c < 8; ++c) mean += frame[static_cast<std::size_t>(r * 8 + c)] / 8;
      EXPECT_NEAR(mean, 0.0, 1e-3);
      for (std::int32_t c = 0; c + 1 < 8; ++c) {
        got.push_back(frame[static_cast<std::size_t>(r * 8 + c + 1)] -
                      frame[static_cast<std::size_t>(r * 8 + c)]);
        want.push_back(1000 * bump.exx(5.0 - 3.5 + c + 0.5, t_s));
      }
    }
  }
  EXPECT_GT(correlation(got, want), 0.98);
}

TEST(MapStrainMovie, IntegratedLeavesUnmeasuredContactorsNeutral) {
  // One row of 12 at 1 mm from x = -0.25 to 10.75 mm on a 10 mm field: the midpoints from 0.25 to
  // 9.25 mm are measured, 10.25 is not, so contactors 0..10 form one zero-mean run and
  // contactor 11 has no measured neighbour.
  MappingParams params;
  params.method = MappingMethod::integrated;
  params.placement = Placement{.centre_x_mm = 5.25, .centre_y_mm = 5.0};
  const auto out = map_strain_movie(uniform_movie(3), grid_layout(1, 12, 1.0, 1.0), params);
  const auto last = out.frame(out.frame_count - 1);
  for (std::size_t c = 0; c <= 10; ++c) {
    EXPECT_NEAR(last[c], 1000 * kA * (static_cast<double>(c) - 5.0), 0.2) << c;
  }
  EXPECT_EQ(last[11], 0.0f);
}

TEST(MapStrainMovie, WorksOnTheBuiltInLayouts) {
  const auto movie = bump_movie(MovingBump{}, 0.7);
  for (const char* name : {"stress", "stress2", "latero"}) {
    const auto layout = movie::layout_by_name(name);
    for (const auto method : {MappingMethod::proportional, MappingMethod::integrated}) {
      MappingParams params;
      params.method = method;
      const auto out = map_strain_movie(movie, layout, params);
      EXPECT_EQ(out.layout.name, name);
      EXPECT_EQ(out.rate_hz, layout.max_rate_hz);  // each layout at its own rate
      // 34/35 s of strain frames at the layout's rate, both ends included.
      EXPECT_EQ(out.frame_count,
                static_cast<std::int32_t>(34.0 / 35.0 * layout.max_rate_hz + 1e-9) + 1);
      EXPECT_NO_THROW(movie::validate_movie(out)) << name << " " << to_string(method);
      float peak = 0;
      for (const float d : out.deflection_um) peak = std::max(peak, std::abs(d));
      EXPECT_GT(peak, 5.0f) << name << " " << to_string(method);
      EXPECT_LE(peak, static_cast<float>(layout.deflection_max_um));
    }
  }
}

TEST(MapStrainMovie, ClampAndSlewLimitHold) {
  const auto movie = uniform_movie(5);
  const auto layout = grid_layout(4, 4, 1.0, 1.0);
  MappingParams params = proportional_params();
  params.gain_um_per_strain = 20000;  // 200 um wanted, 50 allowed
  auto out = map_strain_movie(movie, layout, params);
  for (const float d : out.deflection_um) {
    ASSERT_LE(d, 50.0f);
    ASSERT_GE(d, -50.0f);
  }
  EXPECT_EQ(out.frame(out.frame_count - 1)[0], 50.0f);

  params.gain_um_per_strain = 1000;  // 10 um wanted
  params.slew_limit_um_per_s = 700;  // 1 um per frame
  out = map_strain_movie(movie, layout, params);
  for (std::int32_t f = 0; f < 30; ++f) {
    EXPECT_NEAR(out.frame(f)[5], std::min(f + 1.0, 1000 * kA), 0.05) << f;
  }
}

TEST(MapStrainMovie, PeakNormalisationScalesTheLargestDeflectionToTheRange) {
  MappingParams params;
  params.normalisation = Normalisation::peak;
  params.peak_fraction = 0.8;
  params.gain_um_per_strain = 3;  // irrelevant under "peak"
  const auto out = map_strain_movie(uniform_movie(4), grid_layout(4, 4, 1.0, 1.0), params);
  float peak = 0;
  for (const float d : out.deflection_um) peak = std::max(peak, std::abs(d));
  EXPECT_NEAR(peak, 40.0, 1e-3);
  EXPECT_THAT(out.provenance.parameters_json, HasSubstr("\"normalisation\":\"peak\""));
}

TEST(MapStrainMovie, P99NormalisationIgnoresRareOutliers) {
  // 120 strain frames of uniform 1 % stretch, one of them replaced by a 20 % outlier: 16 of the
  // 1920 values (0.8 %), above the 99th percentile. "p99" scales the 1 % to the target and lets
  // the outlier clamp; "peak" would scale everything to the outlier.
  auto movie = uniform_movie(120, 60.0, 1.0);
  movie.frames[60] = testing::make_frame(
      GridSpec{.spacing_mm = 1.0},
      [](double x, double, double) {
        return PointMm{0.2 * x, 0.0};
      },
      movie.frames[60].t_s, 60, 61);
  const auto layout = grid_layout(4, 4, 1.0, 1.0);
  MappingParams params = proportional_params();
  params.normalisation = Normalisation::p99;
  params.peak_fraction = 0.5;  // target 25 um
  auto out = map_strain_movie(movie, layout, params);
  // Near 25 um: the jittered triangles differ by the O(strain^2) linearisation error.
  EXPECT_NEAR(out.frame(out.frame_count - 1)[5], 25.0, 0.5);
  EXPECT_EQ(out.frame(700)[5], 50.0f);  // t = 61/60 s - 1/60 s = 1 s: the outlier, clamped
  params.normalisation = Normalisation::peak;
  out = map_strain_movie(movie, layout, params);
  EXPECT_LT(out.frame(out.frame_count - 1)[5], 2.0);
}

TEST(MapStrainMovie, RejectsBadParametersAndInputWithClearMessages) {
  const auto movie = uniform_movie(3);
  auto layout = grid_layout(4, 4, 1.0, 1.0);
  layout.max_rate_hz = 700;
  const auto fails_with = [&](const MappingParams& params, const capture::StrainMovie& m,
                              const std::string& text) {
    try {
      (void)map_strain_movie(m, layout, params);
      ADD_FAILURE() << "no exception, expected: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr(text));
    }
  };
  MappingParams p;
  p.rate_hz = 1000;
  fails_with(p, movie, "above layout 'test' maximum rate 700");
  p = {};
  p.rate_hz = 0;
  fails_with(p, movie, "rate_hz must be positive");
  p = {};
  p.rate_hz = 500.5;  // below the maximum, but a device plays whole hertz only
  fails_with(p, movie, "rate 500.5 Hz is not playable: devices play a whole number of hertz");
  p = {};
  p.gain_um_per_strain = -5;
  fails_with(p, movie, "gain_um_per_strain must be positive");
  p = {};
  p.gain_um_per_strain = 0;
  fails_with(p, movie, "gain_um_per_strain must be positive");
  p = {};
  p.peak_fraction = 1.5;
  fails_with(p, movie, "peak_fraction");
  p = {};
  p.slew_limit_um_per_s = 0;
  fails_with(p, movie, "slew_limit_um_per_s");
  p = {};
  p.placement = Placement{.scale = 0};
  fails_with(p, movie, "placement scale");
  fails_with(MappingParams{}, capture::StrainMovie{}, "no strain frames");
  auto backwards = movie;
  backwards.frames[2].t_s = backwards.frames[1].t_s;
  fails_with(MappingParams{}, backwards, "does not follow");
  layout.rows = 0;
  fails_with(MappingParams{}, movie, "0 x 4 contactors");
}

TEST(MapStrainMovie, UnsetRateIsTheLayoutsOwnRate) {
  const auto movie = uniform_movie(10);
  auto layout = grid_layout(4, 4, 1.0, 1.0);
  layout.max_rate_hz = 750;
  const MappingParams params;  // rate_hz unset
  EXPECT_DOUBLE_EQ(resolve_mapping_params(params, layout).rate_hz.value(), 750.0);
  EXPECT_EQ(map_strain_movie(movie, layout, params).rate_hz, 750.0);
  MappingParams given;
  given.rate_hz = 500;
  EXPECT_EQ(map_strain_movie(movie, layout, given).rate_hz, 500.0);
}

}  // namespace
}  // namespace tactile::mapping
