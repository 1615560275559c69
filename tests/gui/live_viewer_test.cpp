// The viewer fed live (as `tactile emulate --latero --window` feeds it): a known frame drawn,
// pixels read back at the contactor positions; the source ends the window. Needs a screen
// (CTest runs the gui tests under Xvfb).
#include <gtest/gtest.h>

#include <cmath>

#include "tactile/display/viewer.hpp"
#include "tactile/movie/frame_geometry.hpp"

namespace tactile::display {
namespace {

TEST(LiveViewer, DrawsWhatTheSourceGivesAtTheContactorPositions) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  const movie::Layout layout = movie::latero_layout();
  LiveFrame frame;
  for (int r = 0; r < 8; ++r) {
    for (int c = 0; c < 8; ++c) frame.deflection_um.push_back(10.0f * static_cast<float>(c));
  }
  frame.lines = {"live"};
  int calls = 0;
  LiveViewerOptions o;
  o.visible = false;
  o.width_px = 400;
  o.height_px = 400;
  o.exit_after_frames = 2;
  const ViewerResult r = run_live_viewer(
      layout,
      [&]() -> std::optional<LiveFrame> {
        ++calls;
        return frame;
      },
      o);
  EXPECT_EQ(calls, 2);
  ASSERT_EQ(r.frames_drawn, 2);
  const RenderedImage& img = r.last_image;
  ASSERT_EQ(img.width, 400);
  const double mag = movie::auto_magnification(layout);
  const movie::ViewTransform t = pane_view(layout, mag, viewer_panes(400, 400, false).contactors);
  for (const movie::ContactorShape& c : movie::frame_shapes(layout, frame.deflection_um, mag)) {
    const int x = static_cast<int>(std::lround(t.origin_x_px + c.x_mm * t.px_per_mm));
    const int y = static_cast<int>(std::lround(t.origin_y_px + c.y_mm * t.px_per_mm));
    const auto px = img.at(x, y);
    // Uniform stretch: every contactor filled with the same stretch colour, not background.
    EXPECT_FALSE(std::abs(px[0] - 64) < 4 && std::abs(px[1] - 64) < 4 && std::abs(px[2] - 64) < 4)
        << "contactor at " << x << "," << y << " not drawn";
  }
}

// A live session's camera: its image (dark left half, bright right half) and a stretched edge
// across it, drawn in the right pane where place_camera puts them.
TEST(LiveViewer, DrawsTheCameraImageWithItsEdgesColouredByStrain) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  const movie::Layout layout = movie::latero_layout();
  LiveFrame frame;
  frame.deflection_um.assign(64, 0.0f);
  CameraView camera;
  camera.width_px = 200;
  camera.height_px = 100;
  for (int y = 0; y < 100; ++y) {
    for (int x = 0; x < 200; ++x) camera.grey.push_back(x < 100 ? 20 : 230);
  }
  camera.full_scale = 0.01;
  camera.edges.push_back({20, 80, 180, 80, 0.01f});  // full stretch, along y = 80
  frame.camera = camera;
  LiveViewerOptions o;
  o.visible = false;
  o.width_px = 600;
  o.height_px = 400;
  o.exit_after_frames = 1;
  const ViewerResult r = run_live_viewer(
      layout, [&]() -> std::optional<LiveFrame> { return frame; }, o);
  ASSERT_EQ(r.frames_drawn, 1);
  const PixelRect pane = viewer_panes(600, 400, true).field;
  ASSERT_GT(pane.width, 0);
  const CameraPlacement at = place_camera(camera, pane);
  const auto pixel = [&](double x, double y) {
    return r.last_image.at(static_cast<int>(std::lround(at.x_px + x * at.scale)),
                           static_cast<int>(std::lround(at.y_px + y * at.scale)));
  };
  const auto dark = pixel(50, 30), bright = pixel(150, 30);
  EXPECT_LT(dark[0], 60);
  EXPECT_GT(bright[0], 190);
  EXPECT_EQ(dark[0], dark[2]);  // grey: the image, not an edge
  const auto expected = movie::strain_colour(0.01, 0.01);
  const auto on_edge = pixel(60, 80);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(on_edge[k], expected[k], 3) << k;
}

TEST(LiveViewer, RefusesACameraViewWhosePixelsDoNotFillIt) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  LiveFrame frame;
  frame.deflection_um.assign(64, 0.0f);
  frame.camera = CameraView{};
  frame.camera->width_px = 10;
  frame.camera->height_px = 10;
  frame.camera->grey.assign(99, 0);
  LiveViewerOptions o;
  o.visible = false;
  EXPECT_THROW(run_live_viewer(
                   movie::latero_layout(), [&]() -> std::optional<LiveFrame> { return frame; }, o),
               std::invalid_argument);
}

TEST(LiveViewer, SourceWithNothingToShowClosesTheWindow) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  LiveViewerOptions o;
  o.visible = false;
  const ViewerResult r = run_live_viewer(
      movie::latero_layout(), []() -> std::optional<LiveFrame> { return std::nullopt; }, o);
  EXPECT_EQ(r.frames_drawn, 0);
}

TEST(LiveViewer, RefusesAFrameOfTheWrongSize) {
  ASSERT_TRUE(screen_available()) << "no screen: run under xvfb-run (CTest does)";
  LiveViewerOptions o;
  o.visible = false;
  EXPECT_THROW(run_live_viewer(
                   movie::latero_layout(),
                   []() -> std::optional<LiveFrame> {
                     return LiveFrame{{1.0f, 2.0f}, {}, std::nullopt};
                   },
                   o),
               std::invalid_argument);
}

}  // namespace
}  // namespace tactile::display
