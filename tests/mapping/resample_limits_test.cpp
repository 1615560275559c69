// Time resampling to the display rate, clamp and slew limit.

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic.hpp"
#include "tactile/mapping/limits.hpp"
#include "tactile/mapping/resample.hpp"

namespace tactile::mapping {
namespace {

TEST(Resample, LinearBetweenCameraFramesAndSpansThemExactly) {
  TimedFrames camera;
  camera.t_s = {0.5, 0.6, 0.8};
  camera.values_per_frame = 2;
  camera.values = {0, 10, 1, 10, 3, -10};
  const auto out = resample_linear(camera, 100.0);
  ASSERT_EQ(out.t_s.size(), 31u);  // 0.5 .. 0.8 s inclusive at 10 ms
  ASSERT_EQ(out.values.size(), 62u);
  EXPECT_DOUBLE_EQ(out.t_s.front(), 0.5);
  EXPECT_NEAR(out.t_s.back(), 0.8, 1e-12);
  // First value: a ramp 0 -> 1 over 0.1 s, then 1 -> 3 over 0.2 s.
  EXPECT_NEAR(out.values[2 * 5], 0.5, 1e-9);   // t = 0.55
  EXPECT_NEAR(out.values[2 * 10], 1.0, 1e-9);  // t = 0.6
  EXPECT_NEAR(out.values[2 * 20], 2.0, 1e-9);  // t = 0.7
  EXPECT_NEAR(out.values[2 * 30], 3.0, 1e-9);  // t = 0.8
  // Second value: 10, 10, then down to -10: 0 at t = 0.7.
  EXPECT_NEAR(out.values[2 * 5 + 1], 10.0, 1e-9);
  EXPECT_NEAR(out.values[2 * 20 + 1], 0.0, 1e-9);
}

TEST(Resample, SingleFrameAndErrors) {
  TimedFrames one{{0.2}, 1, {4.0}};
  const auto out = resample_linear(one, 700);
  ASSERT_EQ(out.values.size(), 1u);
  EXPECT_EQ(out.values[0], 4.0);
  EXPECT_THROW(resample_linear(TimedFrames{}, 700), std::invalid_argument);
  EXPECT_THROW(resample_linear(one, 0), std::invalid_argument);
  EXPECT_THROW(resample_linear(TimedFrames{{0.1, 0.1}, 1, {1, 2}}, 700), std::invalid_argument);
  EXPECT_THROW(resample_linear(TimedFrames{{0.1, 0.2}, 1, {1}}, 700), std::invalid_argument);
}

movie::TactileMovie constant_movie(std::int32_t frames, float value) {
  movie::TactileMovie movie;
  movie.layout = testing::grid_layout(2, 2, 1, 1);
  movie.rate_hz = 700;
  movie.frame_count = frames;
  movie.deflection_um.assign(static_cast<std::size_t>(frames) * 4, value);
  return movie;
}

TEST(Limits, ClampsToTheRangeAndRampsAtTheSlewLimit) {
  const double slew_um_per_s = 7000;  // 10 um per 700 Hz frame
  auto movie = constant_movie(20, 80.0f);
  movie.deflection_um[4 * 15] = std::nanf("");
  const auto out = apply_limits(movie, slew_um_per_s);
  ASSERT_EQ(out.deflection_um.size(), movie.deflection_um.size());
  // From neutral, 10 um per frame up to the +50 um clamp, reached at frame 4.
  for (std::int32_t f = 0; f < 20; ++f) {
    const double expected = std::min(10.0 * (f + 1), 50.0);
    if (f == 15) continue;
    EXPECT_NEAR(out.frame(f)[1], expected, 1e-4) << f;
  }
  // The NaN is sent towards neutral, one slew step, then back.
  EXPECT_NEAR(out.frame(15)[0], 40.0, 1e-4);
  EXPECT_NEAR(out.frame(16)[0], 50.0, 1e-4);
  EXPECT_THROW(apply_limits(movie, 0), std::invalid_argument);
  movie.deflection_um.pop_back();
  EXPECT_THROW(apply_limits(movie, slew_um_per_s), std::invalid_argument);
}

}  // namespace
}  // namespace tactile::mapping
