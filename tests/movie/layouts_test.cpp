// Built-in layouts and movie validation.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "tactile/movie/tactile_movie.hpp"
#include "test_movies.hpp"

namespace tactile::movie {
namespace {

using ::testing::HasSubstr;

TEST(Layouts, MatchThePublishedGeometry) {
  const Layout s = stress_layout();
  EXPECT_EQ(s.contactor_count(), 100);
  EXPECT_DOUBLE_EQ(s.pitch_x_mm, 1.0);
  EXPECT_DOUBLE_EQ(s.max_rate_hz, 700);
  EXPECT_DOUBLE_EQ(s.deflection_max_um, 50);
  const Layout s2 = stress2_layout();
  EXPECT_EQ(s2.contactor_count(), 64);
  EXPECT_DOUBLE_EQ(s2.pitch_x_mm, 1.2);
  EXPECT_DOUBLE_EQ(s2.pitch_y_mm, 1.4);
  const Layout l = latero_layout();
  EXPECT_EQ(l.rows, 8);
  EXPECT_DOUBLE_EQ(l.pitch_y_mm, 1.6125);
  EXPECT_DOUBLE_EQ(l.contactor_width_mm, 0.5);
  EXPECT_DOUBLE_EQ(l.contactor_height_mm, 1.4);
  EXPECT_DOUBLE_EQ(l.max_rate_hz, 750);  // OpenLatero's loop rate
  for (const Layout& x : {s, s2, l}) {
    // Contactors must fit between their neighbours.
    EXPECT_LT(x.contactor_width_mm, x.pitch_x_mm) << x.name;
    EXPECT_LT(x.contactor_height_mm, x.pitch_y_mm) << x.name;
    EXPECT_LT(x.deflection_min_um, 0) << x.name;
    EXPECT_GT(x.deflection_max_um, 0) << x.name;
    EXPECT_EQ(layout_by_name(x.name).name, x.name);
  }
}

TEST(Layouts, UnknownNameListsTheKnownOnes) {
  try {
    layout_by_name("stres");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("stres"));
    EXPECT_THAT(e.what(), HasSubstr("stress2"));
    EXPECT_THAT(e.what(), HasSubstr("latero"));
  }
}

void expect_invalid(const TactileMovie& m, const std::string& words) {
  try {
    validate_movie(m);
    FAIL() << "accepted; expected an error about " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr(words));
  }
}

TEST(Validate, AcceptsAConsistentMovieAndNamesEachInconsistency) {
  const TactileMovie good = testing::sine_movie(stress_layout(), 700, 10, 20);
  EXPECT_NO_THROW(validate_movie(good));
  TactileMovie m = good;
  m.deflection_um.resize(m.deflection_um.size() - 1);
  expect_invalid(m, "999 deflection values");
  m = good;
  m.rate_hz = 0;
  expect_invalid(m, "rate_hz");
  m = good;
  m.layout.rows = 0;
  expect_invalid(m, "0 x 10");
  m = good;
  m.layout.deflection_min_um = 60;
  expect_invalid(m, "deflection range");
  m = good;
  m.deflection_um[3 * 100 + 2 * 10 + 7] = std::numeric_limits<float>::quiet_NaN();
  expect_invalid(m, "frame 3, row 2, col 7");
  m = good;
  m.frame_count = -1;
  expect_invalid(m, "negative");
}

}  // namespace
}  // namespace tactile::movie
