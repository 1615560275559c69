// Tactile movies as perception signals: hand-made movies whose cluster means, activity and
// activity changes are known by hand; bad movies refused by name.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "tactile/perception/movie_signals.hpp"

namespace tactile::perception {
namespace {

using ::testing::HasSubstr;

// A 2 x 12 layout at 700 Hz: columns 0-1 cluster 0, 2-3 cluster 1, ... 10-11 cluster 5.
movie::TactileMovie movie_2x12(std::int32_t frames) {
  movie::TactileMovie m;
  m.layout = movie::stress_layout();
  m.layout.name = "test";
  m.layout.rows = 2;
  m.layout.cols = 12;
  m.layout.deflection_min_um = -100;
  m.layout.deflection_max_um = 100;
  m.rate_hz = 700;
  m.frame_count = frames;
  m.deflection_um.assign(static_cast<std::size_t>(frames) * 24, 0.0f);
  return m;
}

TEST(MovieSignals, ClustersSplitTheColumnsIntoSixBandsAlongX) {
  auto layout = movie::stress_layout();  // 10 columns
  const auto c = contactor_clusters(layout);
  ASSERT_EQ(c.size(), 100u);
  // floor(6 (col + 0.5) / 10): columns 0..9 -> 0 0 1 2 2 3 3 4 5 5, the same on every row.
  const std::vector<int> row = {0, 0, 1, 2, 2, 3, 3, 4, 5, 5};
  for (int r = 0; r < 10; ++r)
    for (int col = 0; col < 10; ++col)
      EXPECT_EQ(c[static_cast<std::size_t>(r * 10 + col)], row[col]);
  layout.cols = 5;
  EXPECT_THROW(
      {
        try {
          contactor_clusters(layout);
        } catch (const std::invalid_argument& e) {
          EXPECT_THAT(e.what(), HasSubstr("5 columns, fewer than the 6 clusters"));
          throw;
        }
      },
      std::invalid_argument);
}

TEST(MovieSignals, ClusterMeansAndActivityOfAConstantPattern) {
  // Every frame: cluster k's contactors at (k + 1) um on row 0 and -(k + 1) / 2 um on row 1, so
  // cluster k's mean is (k + 1) / 4 um and the activity is mean |d| = 3/4 * mean(k + 1) = 2.625.
  auto m = movie_2x12(70);
  for (std::int32_t f = 0; f < m.frame_count; ++f) {
    auto d = m.frame(f);
    for (int col = 0; col < 12; ++col) {
      const float k = static_cast<float>(col / 2 + 1);
      d[static_cast<std::size_t>(col)] = k;
      d[static_cast<std::size_t>(12 + col)] = -k / 2;
    }
  }
  const auto r = movie_signals(m, "hand-made");
  ASSERT_EQ(r.rows(), 10u);  // 70 frames at 700 Hz = 0.1 s = 10 rows of 10 ms
  EXPECT_EQ(r.source, "hand-made");
  ASSERT_EQ(r.vibration.size(), 10u * perception::kVibrationPerRow);
  for (std::size_t i = 0; i < r.rows(); ++i) {
    EXPECT_NEAR(r.t_s[i], i * 0.01, 1e-12);
    EXPECT_NEAR(r.pressure[i], 2.625, 1e-6);
    for (int e = 0; e < perception::kElectrodeCount; ++e)
      EXPECT_NEAR(r.electrodes[static_cast<std::size_t>(e)][i],
                  (perception::kElectrodeCluster[static_cast<std::size_t>(e)] + 1) / 4.0, 1e-6)
          << "electrode " << e;
  }
  for (double v : r.vibration) EXPECT_DOUBLE_EQ(v, 0.0);  // a constant movie does not change
}

TEST(MovieSignals, AMovieSlowerThanTheRowsHoldsEachFrameOnShow) {
  // 40 Hz: frame f starts at 25f ms and every contactor of it is at (f + 1) um. A 10 ms row
  // takes the frame that starts within it (rows 0, 2, 5, 7: frames 0, 1, 2, 3), and a row in
  // which none starts holds the frame on show.
  auto m = movie_2x12(4);
  m.rate_hz = 40;
  for (std::int32_t f = 0; f < m.frame_count; ++f)
    for (auto& v : m.frame(f)) v = static_cast<float>(f + 1);
  const auto r = movie_signals(m, "slow");
  ASSERT_EQ(r.rows(), 10u);  // 4 frames at 40 Hz = 0.1 s
  const double expected[10] = {1, 1, 2, 2, 2, 3, 3, 4, 4, 4};
  for (std::size_t i = 0; i < r.rows(); ++i) {
    EXPECT_NEAR(r.pressure[i], expected[i], 1e-9) << "row " << i;
    EXPECT_NEAR(r.electrodes[0][i], expected[i], 1e-9) << "row " << i;
  }
}

TEST(MovieSignals, RowsAverageTheirFramesAndVibrationIsTheActivityChange) {
  // Every contactor at f um in frame f (a ramp): activity f, change 1 um per frame after frame 0.
  // Row i averages frames 7i .. 7i + 6: activity 7i + 3.
  auto m = movie_2x12(35);
  for (std::int32_t f = 0; f < m.frame_count; ++f)
    for (auto& v : m.frame(f)) v = static_cast<float>(f);
  const auto r = movie_signals(m, "ramp");
  ASSERT_EQ(r.rows(), 5u);
  for (std::size_t i = 0; i < r.rows(); ++i) {
    EXPECT_NEAR(r.pressure[i], 7.0 * i + 3, 1e-9);
    EXPECT_NEAR(r.electrodes[0][i], 7.0 * i + 3, 1e-9);
  }
  ASSERT_EQ(r.vibration.size(), 5u * 22);
  // Sample 0 sits on frame 0 (no change before it); from the first frame on, the change is 1.
  EXPECT_DOUBLE_EQ(r.vibration[0], 0.0);
  for (std::size_t k = 4; k < r.vibration.size(); ++k) EXPECT_NEAR(r.vibration[k], 1.0, 1e-9);
}

TEST(MovieSignals, ContactIsFoundOnTheActivity) {
  // 0.3 s rest, 0.4 s at 5 um, 0.3 s rest: contact rows 30..69.
  auto m = movie_2x12(700);
  for (std::int32_t f = 210; f < 490; ++f)
    for (auto& v : m.frame(f)) v = 5.0f;
  const auto r = movie_signals(m, "pulse");
  const auto c = find_contact(r, movie_contact_options());
  EXPECT_EQ(c.begin, 30u);
  EXPECT_EQ(c.end, 70u);
  EXPECT_DOUBLE_EQ(c.baseline_pressure, 0.0);
}

TEST(MovieSignals, BadMoviesAreRefusedByName) {
  auto m = movie_2x12(3);  // shorter than one row (7 frames)
  EXPECT_THROW(
      {
        try {
          movie_signals(m, "short one");
        } catch (const std::invalid_argument& e) {
          EXPECT_THAT(e.what(), HasSubstr("short one: 3 frames at 700 Hz are shorter than one"));
          throw;
        }
      },
      std::invalid_argument);
  auto bad = movie_2x12(14);
  bad.deflection_um.resize(10);  // sizes do not match the layout
  EXPECT_THROW(movie_signals(bad, "bad"), std::invalid_argument);
  auto nan = movie_2x12(14);
  nan.deflection_um[5] = std::nanf("");
  EXPECT_THROW(movie_signals(nan, "nan"), std::invalid_argument);
}

}  // namespace
}  // namespace tactile::perception
