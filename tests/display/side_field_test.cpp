// The viewer's side field: colour rule, frame choice in time, placement, malformed fields.
#include "tactile/movie/side_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tactile/display/viewer.hpp"

namespace tactile::display {
namespace {

movie::SideField field_of(std::vector<double> times) {
  movie::SideField f;
  f.full_scale = 0.1;
  f.width_mm = 10;
  f.height_mm = 5;
  for (double t : times) f.frames.push_back({t, {{0, 0, 1, 1, 0.05}}});
  return f;
}

TEST(SideField, GreyRunsFromBlackThroughMidGreyToWhiteAndSaturates) {
  // capture's strain maps: -full_scale black, 0 mid grey (255 / 2 rounded), +full_scale white.
  EXPECT_EQ(movie::field_grey(-0.1, 0.1), 0);
  EXPECT_EQ(movie::field_grey(0.0, 0.1), 128);
  EXPECT_EQ(movie::field_grey(0.1, 0.1), 255);
  EXPECT_EQ(movie::field_grey(0.05, 0.1), 191);  // 255 * 0.75 = 191.25
  EXPECT_EQ(movie::field_grey(-5.0, 0.1), 0);
  EXPECT_EQ(movie::field_grey(5.0, 0.1), 255);
}

TEST(SideField, ShowsTheLastFrameStartedAtOrBeforeTheTime) {
  const movie::SideField f = field_of({0.0, 0.1, 0.2});
  EXPECT_EQ(movie::field_frame_at(f, -1.0), 0u);  // before the first: the first
  EXPECT_EQ(movie::field_frame_at(f, 0.0), 0u);
  EXPECT_EQ(movie::field_frame_at(f, 0.0999), 0u);
  EXPECT_EQ(movie::field_frame_at(f, 0.1), 1u);
  EXPECT_EQ(movie::field_frame_at(f, 0.25), 2u);
  EXPECT_EQ(movie::field_frame_at(f, 100.0), 2u);
  EXPECT_THROW(movie::field_frame_at(movie::SideField{}, 0.0), std::invalid_argument);
}

TEST(SideField, FitsUniformlyAndCentred) {
  // 10 x 5 mm into 200 x 200 px: width limits, 200 * 0.88 / 10 = 17.6 px/mm, centred.
  const movie::ViewTransform t = movie::fit_field(field_of({0}), 200, 200);
  EXPECT_DOUBLE_EQ(t.px_per_mm, 17.6);
  EXPECT_DOUBLE_EQ(t.origin_x_px, 12.0);
  EXPECT_DOUBLE_EQ(t.origin_y_px, (200 - 5 * 17.6) / 2);
  const movie::ViewTransform p = pane_field_view(field_of({0}), PixelRect{300, 50, 200, 200});
  EXPECT_DOUBLE_EQ(p.origin_x_px, 312.0);
  EXPECT_DOUBLE_EQ(p.origin_y_px, 50 + (200 - 5 * 17.6) / 2);
}

TEST(SideField, MalformedFieldsAreRefusedWithTheReason) {
  const auto message = [](const movie::SideField& f) {
    try {
      validate_side_field(f);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message(field_of({0, 0.1})), "accepted");
  EXPECT_NE(message(movie::SideField{}).find("no frames"), std::string::npos);
  movie::SideField f = field_of({0, 0.1});
  f.full_scale = 0;
  EXPECT_NE(message(f).find("full scale"), std::string::npos);
  f = field_of({0, 0.1});
  f.full_scale = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(message(f).find("full scale"), std::string::npos);
  f = field_of({0, 0.1});
  f.height_mm = -1;
  EXPECT_NE(message(f).find("extent"), std::string::npos);
  EXPECT_NE(message(field_of({0.1, 0.1})).find("frame 1"), std::string::npos);
  EXPECT_NE(message(field_of({0.2, 0.1})).find("not after"), std::string::npos);
  f = field_of({0});
  f.frames[0].segments[0].x1_mm = std::numeric_limits<double>::infinity();
  EXPECT_NE(message(f).find("non-finite"), std::string::npos);
}

TEST(ViewerLayout, PanesTileTheWindowAndTheScrubBarMapsEndsToFirstAndLastFrame) {
  const ViewerPanes p = viewer_panes(600, 400, true);
  EXPECT_EQ(p.contactors.x + p.contactors.width, p.field.x);
  EXPECT_EQ(p.field.x + p.field.width, 600);
  EXPECT_LE(p.info.y + p.info.height, p.contactors.y);
  EXPECT_LE(p.contactors.y + p.contactors.height, p.scrub.y);
  EXPECT_LE(p.scrub.y + p.scrub.height, 400);
  EXPECT_EQ(viewer_panes(600, 400, false).field.width, 0);
  const PixelRect bar{10, 0, 101, 20};  // 101 px: one pixel per frame of a 101-frame movie
  EXPECT_EQ(scrub_frame(bar, 10, 101), 0);
  EXPECT_EQ(scrub_frame(bar, 110, 101), 100);
  EXPECT_EQ(scrub_frame(bar, 35, 101), 25);
  EXPECT_EQ(scrub_frame(bar, -50, 101), 0);     // left of the bar
  EXPECT_EQ(scrub_frame(bar, 5000, 101), 100);  // right of it
  EXPECT_EQ(scrub_frame(bar, 60, 1), 0);
  EXPECT_DOUBLE_EQ(scrub_handle_x(bar, 25, 101), 35);
}

}  // namespace
}  // namespace tactile::display
