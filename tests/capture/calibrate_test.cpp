#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "tactile/capture/calibrate.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/common/error.hpp"

namespace tactile::capture {
namespace {

TEST(Calibrate, RecoversTheSyntheticCameraFromItsDotGrid) {
  SceneSpec spec;
  spec.frame_count = 1;
  const auto seq = render_sequence(spec);
  const Calibration found = calibrate_dot_grid(seq.dot_grid, 0.5);
  const Calibration& truth = seq.calibration;
  EXPECT_NEAR(found.mm_per_px, truth.mm_per_px, truth.mm_per_px * 1e-3);
  // Lengths across the whole image agree to 0.1 %: what strain measurement needs.
  for (auto [x0, y0, x1, y1] :
       {std::array<double, 4>{0, 0, 639, 0}, {0, 0, 0, 483}, {30, 400, 600, 20}}) {
    const PointMm a = to_mm(found, x0, y0), b = to_mm(found, x1, y1);
    const PointMm ta = to_mm(truth, x0, y0), tb = to_mm(truth, x1, y1);
    const double l = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
    const double tl = std::hypot(tb.x_mm - ta.x_mm, tb.y_mm - ta.y_mm);
    EXPECT_NEAR(l / tl, 1.0, 1e-3);
  }
  const PointMm origin = to_mm(found, 0, 0);
  EXPECT_NEAR(origin.x_mm, 0.0, 1e-9);
  EXPECT_NEAR(origin.y_mm, 0.0, 1e-9);
  EXPECT_EQ(found.image_width_px, 640);
}

TEST(Calibrate, BlankImageIsAFormatErrorSayingNoGrid) {
  GrayImage blank{200, 150, std::vector<std::uint8_t>(200 * 150, 180)};
  EXPECT_THAT([&] { calibrate_dot_grid(blank); },
              ::testing::ThrowsMessage<FormatError>(::testing::HasSubstr("no dot grid found")));
}

TEST(Calibrate, AFingerprintIsNotADotGrid) {
  SceneSpec spec;
  spec.frame_count = 1;
  const auto seq = render_sequence(spec);
  EXPECT_THROW(calibrate_dot_grid(seq.frames[0]), FormatError);
}

}  // namespace
}  // namespace tactile::capture
