// Preview PNG: documented size, real content, colours that follow the strain.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "../common/temp_dir.hpp"
#include "../movie/test_movies.hpp"
#include "tactile/display/preview.hpp"
#include "tactile/movie/frame_geometry.hpp"

namespace tactile::display {
namespace {

namespace fs = std::filesystem;

TEST(FrameGeometry, StrainIsTheRelativeChangeOfNeighbourDistance) {
  movie::Layout l = movie::stress_layout();  // 1 mm pitch along x
  std::vector<float> frame(100, 0);
  for (int c = 0; c < 10; ++c) frame[static_cast<std::size_t>(3 * 10 + c)] = 10.0f * c;
  const auto strain = movie::neighbour_strain(l, frame);
  // Neighbours 1 mm apart move 10 um further apart: 1 % stretch, also at the edges.
  EXPECT_NEAR(strain[3 * 10 + 0], 0.01, 1e-9);
  EXPECT_NEAR(strain[3 * 10 + 5], 0.01, 1e-9);
  EXPECT_NEAR(strain[3 * 10 + 9], 0.01, 1e-9);
  EXPECT_DOUBLE_EQ(strain[4 * 10 + 5], 0);
  const auto shapes = movie::frame_shapes(l, frame, 8);
  EXPECT_NEAR(shapes[3 * 10 + 9].x_mm, 9 + 0.09 * 8, 1e-6);
  EXPECT_DOUBLE_EQ(shapes[3 * 10 + 9].rest_x_mm, 9);
  EXPECT_DOUBLE_EQ(movie::auto_magnification(l), 8);  // 50 um drawn as 0.4 mm
  movie::TactileMovie small;
  small.layout = l;
  small.frame_count = 1;
  small.deflection_um.assign(100, 0.0f);
  EXPECT_DOUBLE_EQ(movie::auto_magnification(small), 8);  // still: falls back to the range
  small.deflection_um[42] = -10.0f;
  EXPECT_DOUBLE_EQ(movie::auto_magnification(small), 40);  // its 10 um peak drawn as 0.4 mm
  EXPECT_EQ(movie::strain_colour(0.01, 0.01), (std::array<std::uint8_t, 3>{255, 0, 0}));
  EXPECT_EQ(movie::strain_colour(-0.02, 0.01), (std::array<std::uint8_t, 3>{0, 0, 255}));
  EXPECT_EQ(movie::strain_colour(0, 0.01), (std::array<std::uint8_t, 3>{255, 255, 255}));
}

TEST(Preview, ImageHasTheDocumentedSizeAndContent) {
  const movie::TactileMovie m = movie::testing::sine_movie(movie::stress_layout(), 700, 700, 40);
  const tactile::test::TempDir dir;
  const fs::path p = dir / "sine.png";
  PreviewOptions o;
  o.frames = 6;
  o.panel_px = 180;
  o.plot_height_px = 150;
  write_preview_strip(p, m, o);
  const cv::Mat img = cv::imread(p.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  EXPECT_EQ(img.cols, 6 * 180);
  EXPECT_EQ(img.rows, kPreviewHeaderPx + 180 + kPreviewLabelPx + 150);
  // Every panel has drawn, coloured contactors: red (stretch) and blue (compression) pixels.
  for (int p_i = 0; p_i < 6; ++p_i) {
    const cv::Mat panel = img(cv::Rect(p_i * 180, kPreviewHeaderPx, 180, 180));
    int red = 0, blue = 0, dark = 0;
    for (int y = 0; y < panel.rows; ++y) {
      for (int x = 0; x < panel.cols; ++x) {
        const cv::Vec3b c = panel.at<cv::Vec3b>(y, x);  // BGR
        red += c[2] > 200 && c[0] < 150;
        blue += c[0] > 200 && c[2] < 150;
        dark += c[0] < 60 && c[1] < 60 && c[2] < 60;
      }
    }
    EXPECT_GT(red, 50) << "panel " << p_i;
    EXPECT_GT(blue, 50) << "panel " << p_i;
    EXPECT_GT(dark, 200) << "panel " << p_i;  // contactor outlines
  }
  // The activity plot has its curve (plot colour, BGR 180, 90, 20).
  const cv::Mat plot = img(cv::Rect(0, img.rows - 150, img.cols, 150));
  int curve = 0;
  for (int y = 0; y < plot.rows; ++y) {
    for (int x = 0; x < plot.cols; ++x) {
      const cv::Vec3b c = plot.at<cv::Vec3b>(y, x);
      curve += c[0] > 120 && c[2] < 100 && c[1] < 140;
    }
  }
  EXPECT_GT(curve, 300);
}

TEST(Preview, UniformStretchIsRedAndAStillMovieIsWhite) {
  movie::TactileMovie m = movie::testing::sine_movie(movie::stress_layout(), 700, 2, 0);
  for (int c = 0; c < 10; ++c) {
    for (int r = 0; r < 10; ++r) m.frame(1)[static_cast<std::size_t>(r * 10 + c)] = 4.0f * c;
  }
  const tactile::test::TempDir dir;
  const fs::path p = dir / "stretch.png";
  PreviewOptions o;
  o.frames = 2;
  write_preview_strip(p, m, o);
  const cv::Mat img = cv::imread(p.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(img.empty());
  // Centre of contactor (5, 5) in each panel. Panel geometry is internal, so look for the
  // dominant non-white colour in the middle tenth of the panel instead of one pixel.
  const auto count = [&](int panel, bool want_red) {
    const cv::Mat mid =
        img(cv::Rect(panel * o.panel_px + o.panel_px * 9 / 20,
                     kPreviewHeaderPx + o.panel_px * 9 / 20, o.panel_px / 10, o.panel_px / 10));
    int n = 0;
    for (int y = 0; y < mid.rows; ++y) {
      for (int x = 0; x < mid.cols; ++x) {
        const cv::Vec3b c = mid.at<cv::Vec3b>(y, x);
        n += want_red ? (c[2] > 200 && c[1] < 80 && c[0] < 80) : (c[0] > 200 && c[2] < 80);
      }
    }
    return n;
  };
  EXPECT_EQ(count(0, true), 0);   // still frame: no stretch colour
  EXPECT_GT(count(1, true), 20);  // uniform 0.4 % stretch: saturated red
  EXPECT_EQ(count(1, false), 0);  // and no compression anywhere
}

TEST(Preview, RejectsBadOptionsAndUnwritablePaths) {
  const movie::TactileMovie m = movie::testing::sine_movie(movie::stress_layout(), 700, 10, 10);
  PreviewOptions o;
  o.frames = 0;
  EXPECT_THROW(write_preview_strip(tactile::test::TempDir() / "x.png", m, o),
               std::invalid_argument);
  EXPECT_THROW(write_preview_strip("/nonexistent_dir/x.png", m), std::runtime_error);
}

}  // namespace
}  // namespace tactile::display
