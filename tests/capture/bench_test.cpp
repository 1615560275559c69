#include "tactile/capture/bench.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace tactile::capture {
namespace {

TEST(CaptureBench, SweepFailuresKeepTheFirstFailureOfEachKind) {
  SweepFailures f;
  f.note(1, true, true);
  f.note(2, false, true);
  EXPECT_FALSE(f.both_failed());
  f.note(3, true, false);  // accuracy recovered: the first failure still counts
  f.note(4, false, false);
  EXPECT_TRUE(f.both_failed());
  EXPECT_EQ(f.accuracy_at, 2);
  EXPECT_EQ(f.yield_at, 3);
  EXPECT_EQ(f.summary("noise", 4),
            "  -> noise: strain error fails at 2; landmark yield fails at 3\n");
  EXPECT_EQ(SweepFailures{}.summary("blur", 5),
            "  -> blur: strain error holds up to 5; landmark yield holds up to 5\n");
}

TEST(CaptureBench, NamesPrintsAndCases) {
  EXPECT_EQ(print_number("image_07.jpg"), "07");
  EXPECT_EQ(case_label({WarpPattern::wave, 0.08, 25}), "wave-fast");
  EXPECT_EQ(case_label({WarpPattern::bump, 0.04, 0}), "bump");
  EXPECT_EQ(case_label({WarpPattern::wave, 0.08, 25, 1.0}), "wave-fast+loss");
  // Every motion of the speed of touch but the plain wave, which the quick bench has.
  for (const auto& c : touch_bench_cases()) {
    EXPECT_GT(c.travel_mm_per_s, 0);
    EXPECT_TRUE(c.pattern != WarpPattern::wave || c.contact_loss > 0);
  }
  // The quick bench is the quasi-static wave and the fast scene; the full one adds the rest.
  EXPECT_EQ(print_bench_cases(true).size(), 2u);
  EXPECT_EQ(print_bench_cases(false).size(), 8u);
  // Full slip at the four speeds of exploring touch, each named by its speed.
  std::vector<std::string> slip;
  for (const auto& c : slip_bench_cases()) {
    EXPECT_EQ(c.pattern, WarpPattern::full_slip);
    slip.push_back(case_label(c));
  }
  EXPECT_EQ(slip, (std::vector<std::string>{"slip-10", "slip-25", "slip-50", "slip-100"}));
}

TEST(CaptureBench, FastSceneSlidesAtTwoAndAHalfMillimetresPerSecond) {
  PrintWarpSpec s;
  s.frame_count = 31;
  s.frame_rate_hz = 60;
  set_fast_scene(s, 25);
  EXPECT_DOUBLE_EQ(s.travel_speed_mm_per_s, 25);
  EXPECT_NEAR(s.slide_x_mm, 2.5 * 30 / 60.0, 1e-12);  // 30 frame intervals at 60 Hz
  EXPECT_DOUBLE_EQ(s.exposure_s, 0.002);
  s.frame_rate_hz = 1000;  // the exposure cannot be longer than a frame
  set_fast_scene(s, 25);
  EXPECT_DOUBLE_EQ(s.exposure_s, 1 / 1000.0);
}

// A 3 x 2 print whose pixels are numbered 0..5 row by row, mirrored into 7 x 5: the copies
// alternate forward and backward in each direction, and a mark keeps the pixel it was on.
TEST(CaptureBench, MirroredPrintRepeatsThePrintAndItsMarksAboutItsEdges) {
  PoreTrainingPrint p;
  p.name = "image_01.png";
  p.image.width_px = 3;
  p.image.height_px = 2;
  p.image.pixels = {0, 1, 2, 3, 4, 5};
  p.pores_px = {{0, 0}, {2, 1}, {1.25, 0.5}};
  const PoreTrainingPrint m = mirrored_to_size(p, 7, 5);
  ASSERT_EQ(m.image.width_px, 7);
  ASSERT_EQ(m.image.height_px, 5);
  EXPECT_EQ(m.name, p.name);
  const std::vector<int> row0 = {0, 1, 2, 2, 1, 0, 0};  // forward, backward, forward
  for (int x = 0; x < 7; ++x) {
    EXPECT_EQ(m.image.at(x, 0), row0[static_cast<std::size_t>(x)]) << x;
    EXPECT_EQ(m.image.at(x, 1), row0[static_cast<std::size_t>(x)] + 3) << x;
    EXPECT_EQ(m.image.at(x, 2), row0[static_cast<std::size_t>(x)] + 3) << x;  // backward in y
    EXPECT_EQ(m.image.at(x, 3), row0[static_cast<std::size_t>(x)]) << x;
    EXPECT_EQ(m.image.at(x, 4), row0[static_cast<std::size_t>(x)]) << x;  // forward again
  }
  for (const auto& [x, y] : m.pores_px) {
    ASSERT_GE(x, 0);
    ASSERT_GE(y, 0);
    ASSERT_LE(x, 6);
    ASSERT_LE(y, 4);
    // Marks on pixel centres sit on the pixel of the same value as in the print.
    if (x == std::floor(x) && y == std::floor(y)) {
      const int v = m.image.at(static_cast<int>(x), static_cast<int>(y));
      EXPECT_TRUE(v == 0 || v == 5) << x << "," << y;
    }
  }
  // 3 copies across (the third cut to one column) x 3 down (the third cut to one row): the
  // corner mark (0, 0) is in all 9 copies, the other two marks only in the 2 x 2 whole ones.
  const auto count = [&](double x, double y) {
    return std::count_if(m.pores_px.begin(), m.pores_px.end(),
                         [&](const auto& q) { return q[0] == x && q[1] == y; });
  };
  EXPECT_EQ(count(0, 0), 1);
  EXPECT_EQ(count(5, 0), 1);       // mirrored in x: 2 w - 1 - 0
  EXPECT_EQ(count(6, 0), 1);       // third copy, forward again
  EXPECT_EQ(count(5, 3), 1);       // mirrored in both
  EXPECT_EQ(count(3.75, 2.5), 1);  // the fractional mark, mirrored in both: (5 - 1.25, 3 - 0.5)
  EXPECT_EQ(m.pores_px.size(), 9u + 4u + 4u);
  EXPECT_THROW(mirrored_to_size(p, 0, 5), std::invalid_argument);
  EXPECT_THROW(mirrored_to_size(p, 7, 20000), std::invalid_argument);
}

TEST(CaptureBench, ScenesRunEveryMethodAndReportFailuresAsRows) {
  std::vector<SceneBenchMethod> methods{
      {"throws", [](const std::vector<GrayImage>&, const Calibration&, double) -> StrainMovie {
         throw std::runtime_error("no luck");
       }}};
  SceneSpec spec;
  spec.frame_count = 3;
  spec.width_px = 64;
  spec.height_px = 48;
  const auto r = run_scene_bench(methods[0], render_sequence(spec));
  EXPECT_EQ(r.method, "throws");
  EXPECT_EQ(r.error, "no luck");
  EXPECT_EQ(r.frames, 3);
}

}  // namespace
}  // namespace tactile::capture
