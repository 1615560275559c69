// The GLFW viewer in a real window: known patterns drawn, pixels read back and checked at
// contactor positions. Skipped when there is no screen (run under Xvfb to exercise it).
#include <gtest/gtest.h>

#include <cmath>

#include "tactile/display/frame_geometry.hpp"
#include "tactile/display/viewer.hpp"
#include "test_movies.hpp"

namespace tactile::display {
namespace {

bool is_red(std::array<std::uint8_t, 3> c) {
  return c[0] > 200 && c[1] < 80 && c[2] < 80;
}
bool is_white(std::array<std::uint8_t, 3> c) {
  return c[0] > 240 && c[1] > 240 && c[2] > 240;
}
bool is_background(std::array<std::uint8_t, 3> c) {
  return std::abs(c[0] - 64) < 4 && std::abs(c[1] - 64) < 4 && std::abs(c[2] - 64) < 4;
}

TEST(Viewer, DrawsAKnownPatternAtTheContactorPositions) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  // Frame 1: uniform stretch along x, every contactor 4 um per column further right.
  TactileMovie m = testing::sine_movie(stress_layout(), 700, 2, 0);
  for (int r = 0; r < 10; ++r) {
    for (int c = 0; c < 10; ++c) m.frame(1)[static_cast<std::size_t>(r * 10 + c)] = 4.0f * c;
  }
  ViewerOptions o;
  o.through_device = false;
  o.visible = false;
  o.fixed_step = true;
  o.exit_after_frames = 2;  // frame 0 then frame 1, whose pixels are read back
  o.width_px = 400;
  o.height_px = 400;
  const ViewerResult r = run_viewer(m, o);
  ASSERT_EQ(r.frames_drawn, 2);
  EXPECT_EQ(r.last_movie_frame, 1);
  const RenderedImage& img = r.last_image;
  ASSERT_EQ(img.width, 400);
  ASSERT_EQ(img.height, 400);
  const double mag = auto_magnification(m.layout);
  const ViewTransform t = fit_view(m.layout, mag, img.width, img.height);
  for (const ContactorShape& c : frame_shapes(m.layout, m.frame(1), mag)) {
    const int x = static_cast<int>(std::lround(t.origin_x_px + c.x_mm * t.px_per_mm));
    const int y = static_cast<int>(std::lround(t.origin_y_px + c.y_mm * t.px_per_mm));
    EXPECT_TRUE(is_red(img.at(x + 2, y + 2))) << "contactor centre " << x << "," << y;
    // Halfway between rows there is only background.
    const int gap_y = static_cast<int>(std::lround(t.origin_y_px + (c.y_mm + 0.5) * t.px_per_mm));
    if (gap_y < img.height) {
      EXPECT_TRUE(is_background(img.at(x, gap_y)));
    }
  }
}

TEST(Viewer, ShowsTheFirmwareClampNotTheRawMovie) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  // Every contactor asked for +80 um; the STReSS firmware clamps at +50 um. Uniform
  // deflection means no strain: white contactors.
  TactileMovie m = testing::sine_movie(stress_layout(), 700, 20, 0);
  for (float& v : m.deflection_um) v = 80;
  ViewerOptions o;
  o.play.allow_out_of_range = true;
  o.play.ramp_s = 0;
  o.visible = false;
  o.fixed_step = true;
  o.exit_after_frames = 10;
  o.width_px = 400;
  o.height_px = 400;
  const ViewerResult r = run_viewer(m, o);
  const RenderedImage& img = r.last_image;
  const double mag = auto_magnification(m.layout);  // 8: 50 um -> 0.4 mm
  const ViewTransform t = fit_view(m.layout, mag, img.width, img.height);
  const auto pixel = [&](double x_mm, double y_mm) {
    return img.at(static_cast<int>(std::lround(t.origin_x_px + x_mm * t.px_per_mm)),
                  static_cast<int>(std::lround(t.origin_y_px + y_mm * t.px_per_mm)));
  };
  // Contactor (5, 5) rests at (5, 5) mm and is 0.5 mm wide. Clamped: it spans 5.15..5.65 mm;
  // unclamped it would span 5.39..5.89 mm.
  EXPECT_TRUE(is_white(pixel(5.25, 5.0)));       // inside only the clamped position
  EXPECT_TRUE(is_background(pixel(5.75, 5.0)));  // inside only the unclamped position
}

}  // namespace
}  // namespace tactile::display
