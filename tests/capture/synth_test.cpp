#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "tactile/capture/synth.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

SceneSpec tiny(const std::string& scene) {
  SceneSpec s;
  s.scene = scene;
  s.frame_count = 4;
  return s;
}

TEST(Synth, SameSeedSamePixelsOtherSeedOtherPixels) {
  const auto a = render_sequence(tiny("bump"));
  const auto b = render_sequence(tiny("bump"));
  SceneSpec other = tiny("bump");
  other.seed = 2;
  const auto c = render_sequence(other);
  ASSERT_EQ(a.frames.size(), 4u);
  EXPECT_EQ(a.frames[3].pixels, b.frames[3].pixels);
  EXPECT_NE(a.frames[3].pixels, c.frames[3].pixels);
  EXPECT_EQ(a.frames[0].width_px, 640);
  EXPECT_EQ(a.frames[0].height_px, 484);
}

TEST(Synth, FlatSlideMovesEveryPointBySpeedOverRate) {
  const SceneSpec s = tiny("flat-slide");
  const PointMm skin{3.0, 4.0};
  const PointMm p0 = skin_to_image(s, skin, 0);
  const PointMm p3 = skin_to_image(s, skin, 3);
  EXPECT_NEAR(p3.x_mm - p0.x_mm, 3 * s.speed_mm_per_s / s.frame_rate_hz, 1e-12);
  EXPECT_NEAR(p3.y_mm - p0.y_mm, 0.0, 1e-12);
  EXPECT_NEAR(true_rel_change(s, {1, 1}, {2, 3}, 0, 3), 0.0, 1e-12);
}

TEST(Synth, SkinAndImageMapsAreInverse) {
  const SceneSpec s = tiny("bump");
  for (double x : {2.0, 4.5, 5.1, 6.0}) {
    for (int frame : {0, 2}) {
      const PointMm image{x, 5.4};
      const PointMm back = skin_to_image(s, image_to_skin(s, image, frame), frame);
      EXPECT_NEAR(back.x_mm, image.x_mm, 1e-10);
      EXPECT_NEAR(back.y_mm, image.y_mm, 1e-10);
    }
  }
}

// Over the bump's top the skin is stretched radially (d = A r/sigma exp(..) grows with r), so a
// short segment there is longer than the same skin far away; for the hole, shorter.
TEST(Synth, BumpStretchesAndHoleCompressesTheSkinOverTheFeature) {
  for (const char* scene : {"bump", "hole"}) {
    const SceneSpec s = tiny(scene);
    const double cx = (s.width_px - 1) * s.field_width_mm / s.width_px / 2;
    const double cy = (s.height_px - 1) * s.field_height_mm / s.height_px / 2;
    const PointMm a = image_to_skin(s, {cx - 0.1, cy}, 0);
    const PointMm b = image_to_skin(s, {cx + 0.1, cy}, 0);
    const double skin_length = std::hypot(b.x_mm - a.x_mm, b.y_mm - a.y_mm);
    if (std::string(scene) == "bump") {
      EXPECT_LT(skin_length, 0.2 * 0.95) << "image segment should show stretched (shorter) skin";
    } else {
      EXPECT_GT(skin_length, 0.2 * 1.05);
    }
  }
}

TEST(Synth, RenderedPoresAreBrightSpotsAtTheirTruePositions) {
  const auto seq = render_sequence(tiny("bump"));
  int pores = 0, bright = 0;
  for (const auto& lm : seq.landmarks) {
    if (lm.frame != 2 || lm.type != FeatureType::pore || lm.diameter_mm < 0.12) continue;
    const int x = static_cast<int>(std::lround(lm.x_px));
    const int y = static_cast<int>(std::lround(lm.y_px));
    if (x < 8 || y < 8 || x >= 632 || y >= 476) continue;
    ++pores;
    // The pore centre must outshine the dark ridge around it, sampled ~0.11 mm away across.
    const auto& f = seq.frames[2];
    const int ring = f.at(x + 7, y) + f.at(x - 7, y) + f.at(x, y + 5) + f.at(x, y - 5);
    if (f.at(x, y) * 4 > ring + 4 * 20) ++bright;
  }
  ASSERT_GT(pores, 30);
  EXPECT_GT(bright, pores * 0.8) << bright << " of " << pores;
}

TEST(Synth, LandmarksOnlyWhereSkinTouchesTheGlass) {
  const auto seq = render_sequence(tiny("bump"));
  for (const auto& lm : seq.landmarks) {
    ASSERT_TRUE(in_contact(seq.spec, {lm.x_mm, lm.y_mm}, lm.frame));
  }
}

TEST(Synth, WriteSequenceWritesFramesGroundTruthAndScene) {
  testing::TempDir dir;
  const auto seq = render_sequence(tiny("hole"));
  write_sequence(dir.path(), seq);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "frame_000.png"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "frame_003.png"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "calibration" / "dot_grid.png"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "scene.json"));
  std::ifstream csv(dir.path() / "landmarks.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "id,type,frame,x_px,y_px,x_mm,y_mm,diameter_mm");
  std::size_t rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, seq.landmarks.size());
}

TEST(Synth, BadSpecIsRejectedWithTheFieldName) {
  SceneSpec s = tiny("volcano");
  EXPECT_THAT([&] { render_sequence(s); },
              ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("volcano")));
  s = tiny("bump");
  s.frame_rate_hz = 0;
  EXPECT_THAT([&] { render_sequence(s); }, ::testing::ThrowsMessage<std::invalid_argument>(
                                               ::testing::HasSubstr("frame_rate_hz")));
}

}  // namespace
}  // namespace tactile::capture
