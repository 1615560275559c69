#include "tactile/capture/strain_map.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tactile/capture/image.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

using ::testing::HasSubstr;

// Four points on a square; edges stretched by 10 %, compressed by 10 % and unchanged.
StrainFrame square_frame() {
  StrainFrame f;
  f.frame_from = 3;
  f.frame_to = 4;
  const double xy[4][2] = {{100, 100}, {300, 100}, {100, 300}, {300, 300}};
  for (int i = 0; i < 4; ++i) {
    TrackedPoint p;
    p.track_id = 10 + i;
    p.x_px = xy[i][0];
    p.y_px = xy[i][1];
    f.points_to.push_back(p);
  }
  f.points_from = f.points_to;
  f.edges = {{10, 11, 4, 4.4, 0.1}, {10, 12, 4, 3.6, -0.1}, {11, 13, 4, 4, 0.0}};
  return f;
}

TEST(StrainMap, EdgesGoFromBlackThroughGreyToWhite) {
  testing::TempDir dir;
  const auto png = dir.path() / "map.png";
  write_strain_map_png(png, square_frame(), uniform_calibration(50, 400, 400),
                       StrainMapOptions{.full_scale = 0.1, .line_width_px = 3});
  const GrayImage image = read_image(png);
  ASSERT_EQ(image.width_px, 400);
  ASSERT_EQ(image.height_px, 400);
  EXPECT_GE(image.at(200, 100), 240);       // +10 % at full scale: white
  EXPECT_LE(image.at(100, 200), 15);        // -10 %: black
  EXPECT_NEAR(image.at(300, 200), 128, 3);  // unchanged: mid grey
  EXPECT_GT(image.at(200, 300), 15);        // no edge there: background, not black
  EXPECT_LT(image.at(200, 300), 100);
}

TEST(StrainMap, FullScaleIsThe99thPercentileOfEdgeStrain) {
  StrainMovie movie;
  EXPECT_EQ(strain_map_full_scale(movie), 0);
  movie.frames.resize(2);
  for (int i = 1; i <= 100; ++i) {
    StrainEdge e;
    e.rel_change = (i % 2 ? -1 : 1) * 0.001 * i;  // magnitudes 0.001 .. 0.100
    movie.frames[static_cast<std::size_t>(i % 2)].edges.push_back(e);
  }
  // 100 magnitudes: index floor(0.99 * 99) = 98 of the sorted list is 0.099.
  EXPECT_DOUBLE_EQ(strain_map_full_scale(movie), 0.099);
}

TEST(StrainMap, BadInputIsNamed) {
  testing::TempDir dir;
  const Calibration c = uniform_calibration(50, 400, 400);
  StrainFrame f = square_frame();
  f.edges.push_back({10, 99, 4, 4, 0});
  try {
    write_strain_map_png(dir.path() / "a.png", f, c, {.full_scale = 0.1});
    FAIL() << "an edge to a missing track was drawn";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("10-99"));
  }
  EXPECT_THROW(write_strain_map_png(dir.path() / "b.png", square_frame(), c, {.full_scale = 0}),
               std::invalid_argument);
  try {
    write_strain_map_png("/nonexistent-dir/map.png", square_frame(), c, {.full_scale = 0.1});
    FAIL() << "an unwritable path was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent-dir/map.png"));
  }
}

}  // namespace
}  // namespace tactile::capture
