// The GLFW viewer in a real window: known patterns drawn, pixels read back and checked at
// contactor positions. Skipped when there is no screen (run under Xvfb to exercise it).
#include <gtest/gtest.h>

#include <cmath>

#include "../movie/test_movies.hpp"
#include "tactile/display/viewer.hpp"
#include "tactile/movie/frame_geometry.hpp"

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
  movie::TactileMovie m = movie::testing::sine_movie(movie::stress_layout(), 700, 2, 0);
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
  const double mag = movie::auto_magnification(m.layout);
  const movie::ViewTransform t = pane_view(m.layout, mag, viewer_panes(400, 400, false).contactors);
  for (const movie::ContactorShape& c : movie::frame_shapes(m.layout, m.frame(1), mag)) {
    const int x = static_cast<int>(std::lround(t.origin_x_px + c.x_mm * t.px_per_mm));
    const int y = static_cast<int>(std::lround(t.origin_y_px + c.y_mm * t.px_per_mm));
    EXPECT_TRUE(is_red(img.at(x + 2, y + 2))) << "contactor centre " << x << "," << y;
    // Halfway between rows there is only background.
    const int gap_y = static_cast<int>(std::lround(t.origin_y_px + (c.y_mm + 0.5) * t.px_per_mm));
    const PixelRect pane = viewer_panes(400, 400, false).contactors;
    if (gap_y < pane.y + pane.height - 10) {
      EXPECT_TRUE(is_background(img.at(x, gap_y)));
    }
  }
}

TEST(Viewer, ShowsTheFirmwareClampNotTheRawMovie) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  // Every contactor asked for +80 um; the STReSS firmware clamps at +50 um. Uniform
  // deflection means no strain: white contactors.
  movie::TactileMovie m = movie::testing::sine_movie(movie::stress_layout(), 700, 20, 0);
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
  const double mag = movie::auto_magnification(m.layout);  // 8: 50 um -> 0.4 mm
  const movie::ViewTransform t = pane_view(m.layout, mag, viewer_panes(400, 400, false).contactors);
  const auto pixel = [&](double x_mm, double y_mm) {
    return img.at(static_cast<int>(std::lround(t.origin_x_px + x_mm * t.px_per_mm)),
                  static_cast<int>(std::lround(t.origin_y_px + y_mm * t.px_per_mm)));
  };
  // Contactor (5, 5) rests at (5, 5) mm and is 0.5 mm wide. Clamped: it spans 5.15..5.65 mm;
  // unclamped it would span 5.39..5.89 mm.
  EXPECT_TRUE(is_white(pixel(5.25, 5.0)));  // inside only the clamped position
  // What the text strip reports at this frame: streaming, 100 samples clamped per frame.
  EXPECT_TRUE(r.last_device_tick.streaming);
  EXPECT_EQ(r.last_device_tick.clamped_samples % 100, 0u);
  EXPECT_GE(r.last_device_tick.clamped_samples, 500u);
  EXPECT_TRUE(is_background(pixel(5.75, 5.0)));  // inside only the unclamped position
}

// A movie whose every frame is a uniform deflection that grows with the frame index: the
// displayed frame is read off the contactors' position.
movie::TactileMovie ramp_movie(std::int32_t frames) {
  movie::TactileMovie m = movie::testing::sine_movie(movie::stress_layout(), 700, frames, 0);
  for (std::int32_t f = 0; f < frames; ++f) {
    const float d = -45.0f + 90.0f * static_cast<float>(f) / static_cast<float>(frames - 1);
    for (std::size_t i = 0; i < 100; ++i)
      m.deflection_um[static_cast<std::size_t>(f) * 100 + i] = d;
  }
  return m;
}

TEST(Viewer, ScrubBarSeeksToTheClickedFrameAndShowsIt) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  const std::int32_t frames = 101;
  const movie::TactileMovie m = ramp_movie(frames);
  const ViewerPanes panes = viewer_panes(400, 400, false);
  // Click a quarter of the way along the bar, drag to three quarters, release.
  const PixelRect& bar = panes.scrub;
  const double y = bar.y + bar.height / 2.0;
  const double x_quarter = bar.x + 0.25 * (bar.width - 1);
  const double x_three_quarters = bar.x + 0.75 * (bar.width - 1);
  ViewerOptions o;
  o.through_device = false;
  o.visible = false;
  o.fixed_step = true;
  o.start_paused = true;
  o.width_px = 400;
  o.height_px = 400;
  o.scripted_pointer = {
      {0, x_quarter, y, true}, {2, x_three_quarters, y, true}, {3, x_three_quarters, y, false}};
  o.exit_after_frames = 1;  // the press at a quarter
  ViewerResult r = run_viewer(m, o);
  EXPECT_EQ(r.last_movie_frame, 25);  // 0.25 * 100
  o.exit_after_frames = 5;            // dragged to three quarters, released, still paused there
  r = run_viewer(m, o);
  ASSERT_EQ(r.last_movie_frame, 75);
  const RenderedImage& img = r.last_image;
  // Frame 75 deflects every contactor by -45 + 90 * 0.75 = +22.5 um; x8: +0.18 mm. Contactor
  // (5, 5) (rest 5.0 mm, 0.5 mm wide) then spans 4.93..5.43 mm; frame 0 would put it at
  // 4.39..4.89 mm.
  const double mag = movie::auto_magnification(m.layout);
  ASSERT_DOUBLE_EQ(mag, 8.0);
  const movie::ViewTransform t = pane_view(m.layout, mag, panes.contactors);
  const auto pixel = [&](double x_mm, double y_mm) {
    return img.at(static_cast<int>(std::lround(t.origin_x_px + x_mm * t.px_per_mm)),
                  static_cast<int>(std::lround(t.origin_y_px + y_mm * t.px_per_mm)));
  };
  EXPECT_TRUE(is_white(pixel(5.30, 5.1)));       // uniform deflection: no strain, white
  EXPECT_TRUE(is_background(pixel(4.60, 5.1)));  // where frame 0 would be
  // The bar: played part left of the handle, the rest right of it.
  const int handle = static_cast<int>(std::lround(x_three_quarters));
  const auto played = img.at(handle - 8, static_cast<int>(y));
  const auto rest = img.at(handle + 8, static_cast<int>(y));
  EXPECT_EQ(played, (std::array<std::uint8_t, 3>{70, 130, 200}));
  EXPECT_EQ(rest, (std::array<std::uint8_t, 3>{40, 40, 40}));
  EXPECT_TRUE(is_white(img.at(handle, static_cast<int>(y))));
}

TEST(Viewer, InfoStripCarriesText) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  ViewerOptions o;
  o.visible = false;
  o.fixed_step = true;
  o.exit_after_frames = 3;
  o.width_px = 400;
  o.height_px = 400;
  const ViewerResult r =
      run_viewer(movie::testing::sine_movie(movie::stress_layout(), 700, 20, 10), o);
  // Dear ImGui's text is light grey on its dark window: some bright pixels in the strip, none
  // of them in the strip of an empty window would be.
  const PixelRect info = viewer_panes(400, 400, false).info;
  int bright = 0;
  for (int y = info.y; y < info.y + info.height; ++y) {
    for (int x = info.x; x < info.x + info.width; ++x) {
      const auto c = r.last_image.at(x, y);
      bright += (c[0] > 180 && c[1] > 180 && c[2] > 180) ? 1 : 0;
    }
  }
  EXPECT_GT(bright, 200);
  EXPECT_GT(r.device_report.frames_played, 0);  // counters shown come from the firmware
}

// Two frames of a two-edge field: the horizontal edge stretched and the vertical one
// compressed, then the other way round from t = 0.05 s.
movie::SideField two_edge_field() {
  movie::SideField f;
  f.title = "strain";
  f.full_scale = 0.1;
  f.width_mm = 10;
  f.height_mm = 10;
  f.frames.push_back({0.0, {{2, 3, 8, 3, +0.1}, {5, 5, 5, 9, -0.1}}});
  f.frames.push_back({0.05, {{2, 3, 8, 3, -0.1}, {5, 5, 5, 9, +0.1}}});
  return f;
}

TEST(Viewer, DrawsTheSourceFieldBesideTheArrayInStep) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  const movie::TactileMovie m =
      movie::testing::sine_movie(movie::stress_layout(), 100, 10, 10);  // 10 ms frames
  ViewerOptions o;
  o.through_device = false;
  o.visible = false;
  o.fixed_step = true;
  o.start_paused = true;
  o.width_px = 300;  // the field doubles the window's width
  o.height_px = 400;
  o.field = two_edge_field();
  const ViewerPanes panes = viewer_panes(600, 400, true);
  const movie::ViewTransform t = pane_field_view(*o.field, panes.field);
  const auto pixel = [&](const RenderedImage& img, double x_mm, double y_mm) {
    return img.at(static_cast<int>(std::lround(t.origin_x_px + x_mm * t.px_per_mm)),
                  static_cast<int>(std::lround(t.origin_y_px + y_mm * t.px_per_mm)));
  };
  const auto grey = [](std::array<std::uint8_t, 3> c) { return (c[0] + c[1] + c[2]) / 3; };
  o.exit_after_frames = 1;  // t = 0: first field frame
  ViewerResult r = run_viewer(m, o);
  ASSERT_EQ(r.last_image.width, 600);
  EXPECT_EQ(r.last_field_frame, 0u);
  EXPECT_GT(grey(pixel(r.last_image, 5, 3)), 240);  // stretched: white
  EXPECT_LT(grey(pixel(r.last_image, 5, 7)), 15);   // compressed: black
  const auto bg = pixel(r.last_image, 8, 8);        // no edge: the field's background
  EXPECT_EQ(bg, (std::array<std::uint8_t, 3>{20, 40, 70}));
  // Scrub to frame 6 (t = 0.06 s): the second field frame, edges swapped.
  const double y = panes.scrub.y + panes.scrub.height / 2.0;
  o.scripted_pointer = {{0, scrub_handle_x(panes.scrub, 6, 10), y, true}};
  o.exit_after_frames = 2;
  r = run_viewer(m, o);
  ASSERT_EQ(r.last_movie_frame, 6);
  EXPECT_EQ(r.last_field_frame, 1u);
  EXPECT_LT(grey(pixel(r.last_image, 5, 3)), 15);
  EXPECT_GT(grey(pixel(r.last_image, 5, 7)), 240);
}

TEST(Viewer, RefusesAMalformedField) {
  movie::SideField f = two_edge_field();
  f.frames[1].t_s = 0;  // not after the first
  ViewerOptions o;
  o.visible = false;
  o.field = f;
  EXPECT_THROW(run_viewer(movie::testing::sine_movie(movie::stress_layout(), 100, 10, 10), o),
               std::invalid_argument);
}

}  // namespace
}  // namespace tactile::display
