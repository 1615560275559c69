// Movie summary values for synthetic movies whose statistics are known in closed form.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "../movie/test_movies.hpp"
#include "tactile/display/summary.hpp"

namespace tactile::display {
namespace {

using ::testing::HasSubstr;

TEST(Summary, SineOfKnownAmplitude) {
  // 2 s at 700 Hz of a 5 Hz sine of 30 um: whole periods, so RMS = 30 / sqrt(2) exactly
  // (up to float rounding) and every 0.1 s window holds half a period: the same RMS.
  const movie::TactileMovie m =
      movie::testing::sine_movie(movie::stress_layout(), 700, 1400, 30, 5);
  const MovieSummary s = summarize(m);
  EXPECT_EQ(s.layout_name, "stress");
  EXPECT_EQ(s.frame_count, 1400);
  EXPECT_DOUBLE_EQ(s.duration_s, 2.0);
  EXPECT_NEAR(s.rms_deflection_um, 30 / std::sqrt(2.0), 1e-3);
  EXPECT_NEAR(s.peak_deflection_um, 30, 0.01);
  EXPECT_LE(s.peak_deflection_um, 30.0 + 1e-5);
  EXPECT_DOUBLE_EQ(s.saturated_fraction, 0);
  ASSERT_EQ(s.activity_rms_um.size(), 20u);
  for (double a : s.activity_rms_um) EXPECT_NEAR(a, 30 / std::sqrt(2.0), 0.05);
}

TEST(Summary, ActivityFollowsAnEnvelopeAndSaturationIsCounted) {
  // 0.5 s still, then 0.5 s with every contactor at the +50 um limit.
  movie::TactileMovie m = movie::testing::sine_movie(movie::stress_layout(), 700, 700, 0);
  for (std::int32_t f = 350; f < 700; ++f) {
    for (float& v : m.frame(f)) v = 50;
  }
  const MovieSummary s = summarize(m);
  ASSERT_EQ(s.activity_rms_um.size(), 10u);
  for (int w = 0; w < 5; ++w) EXPECT_DOUBLE_EQ(s.activity_rms_um[w], 0) << w;
  for (int w = 5; w < 10; ++w) EXPECT_DOUBLE_EQ(s.activity_rms_um[w], 50) << w;
  EXPECT_DOUBLE_EQ(s.saturated_fraction, 0.5);
  EXPECT_DOUBLE_EQ(s.peak_frame_rms_um, 50);
  EXPECT_DOUBLE_EQ(s.peak_frame_t_s, 0.5);
  const std::string text = format_summary(s);
  EXPECT_THAT(text, HasSubstr("stress (10 x 10 contactors)"));
  EXPECT_THAT(text, HasSubstr("700 movie frames at 700 Hz = 1.000 s"));
  EXPECT_THAT(text, HasSubstr("50.00 % of samples"));
  EXPECT_THAT(text, HasSubstr("|     #####|"));
}

TEST(Summary, RefusesAnInvalidMovie) {
  movie::TactileMovie m = movie::testing::sine_movie(movie::stress_layout(), 700, 10, 1);
  m.frame_count = 11;
  EXPECT_THROW(summarize(m), std::invalid_argument);
}

}  // namespace
}  // namespace tactile::display
