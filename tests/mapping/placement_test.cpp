// Registration of the contactor grid on the field.

#include <gtest/gtest.h>

#include <numbers>

#include "synthetic.hpp"
#include "tactile/mapping/placement.hpp"

namespace tactile::mapping {
namespace {

TEST(Placement, DefaultCentresThePhysicalSizeGridOnTheField) {
  capture::StrainMovie movie;
  movie.field_width_mm = 10.3;
  movie.field_height_mm = 10.9;
  const auto p = default_placement(movie);
  EXPECT_DOUBLE_EQ(p.centre_x_mm, 5.15);
  EXPECT_DOUBLE_EQ(p.centre_y_mm, 5.45);
  EXPECT_EQ(p.rotation_rad, 0.0);
  EXPECT_EQ(p.scale, 1.0);

  const auto layout = testing::grid_layout(10, 10, 1.0, 1.0);
  const auto first = contactor_position_mm(layout, p, 0, 0);
  const auto last = contactor_position_mm(layout, p, 9, 9);
  EXPECT_DOUBLE_EQ(first.x_mm, 5.15 - 4.5);
  EXPECT_DOUBLE_EQ(first.y_mm, 5.45 - 4.5);
  EXPECT_DOUBLE_EQ(last.x_mm, 5.15 + 4.5);
  EXPECT_DOUBLE_EQ(last.y_mm, 5.45 + 4.5);
}

TEST(Placement, DefaultFollowsTheCalibrationsOrigin) {
  capture::StrainMovie movie;
  // 640 x 484 px at 0.016 mm/px with the origin moved to (-2, 1) mm.
  movie.calibration.px_to_mm = {0.016, 0, -2.0, 0, 0.016, 1.0, 0, 0, 1};
  movie.calibration.image_width_px = 640;
  movie.calibration.image_height_px = 484;
  movie.field_width_mm = 639 * 0.016;
  movie.field_height_mm = 483 * 0.016;
  const auto p = default_placement(movie);
  EXPECT_NEAR(p.centre_x_mm, -2.0 + 319.5 * 0.016, 1e-12);
  EXPECT_NEAR(p.centre_y_mm, 1.0 + 241.5 * 0.016, 1e-12);
}

TEST(Placement, DefaultWithoutFieldSizeUsesTheTrackedPoints) {
  capture::StrainMovie movie;
  movie.tracks = {{0, 0, {}, 0, 0, 1.0, 2.0}, {1, 0, {}, 0, 0, 5.0, 4.0}};
  const auto p = default_placement(movie);
  EXPECT_DOUBLE_EQ(p.centre_x_mm, 3.0);
  EXPECT_DOUBLE_EQ(p.centre_y_mm, 3.0);
}

TEST(Placement, RotationAndScaleMoveContactorsAboutTheCentre) {
  const auto layout = testing::grid_layout(2, 3, 1.2, 1.4);  // centre between rows 0/1, at col 1
  const Placement p{
      .centre_x_mm = 4, .centre_y_mm = 5, .rotation_rad = std::numbers::pi / 2, .scale = 2};
  // Contactor (0, 2) is +1.2 mm along the layout's x and -0.7 mm along its y from the centre;
  // scaled by 2 and turned a quarter (layout x -> field +y, layout y -> field -x).
  const auto q = contactor_position_mm(layout, p, 0, 2);
  EXPECT_NEAR(q.x_mm, 4 + 1.4, 1e-12);
  EXPECT_NEAR(q.y_mm, 5 + 2.4, 1e-12);
  const auto all = contactor_positions_mm(layout, p);
  ASSERT_EQ(all.size(), 6u);
  EXPECT_DOUBLE_EQ(all[2].x_mm, q.x_mm);
  EXPECT_DOUBLE_EQ(all[2].y_mm, q.y_mm);
}

}  // namespace
}  // namespace tactile::mapping
