#include "tactile/capture/bench.hpp"

#include <gtest/gtest.h>

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
