#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>

#include "tactile/capture/synth.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

SceneSpec tiny(const std::string& scene) {
  SceneSpec s;
  s.scene = parse_scene(scene);
  s.frame_count = 4;
  return s;
}

// Scene names are those of `--scene` and of scene and experiment files: each reads back as
// itself, and an unknown one is refused with the known ones listed.
TEST(Synth, SceneNamesRoundTripAndAnUnknownNameListsTheKnownOnes) {
  for (const char* name : {"bump", "hole", "flat-slide", "flat-rotate", "flat-stick-slip"})
    EXPECT_EQ(to_string(parse_scene(name)), name);
  EXPECT_EQ(parse_scene("flat-stick-slip"), Scene::flat_stick_slip);
  try {
    parse_scene("cube");
    ADD_FAILURE() << "'cube' was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "unknown scene 'cube' (known: bump, hole, flat-slide, flat-rotate, "
                 "flat-stick-slip)");
  }
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

// The partial-slip scenes press the finger in place; the patch is centred in the field.
PointMm field_centre(const SceneSpec& s) {
  return {(s.width_px - 1) * s.field_width_mm / s.width_px / 2,
          (s.height_px - 1) * s.field_height_mm / s.height_px / 2};
}

double smoothstep(double lo, double hi, double v) {
  const double t = std::clamp((v - lo) / (hi - lo), 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

// Press and rotate: the stick region does not move, skin at and beyond the patch edge turns
// rigidly with the finger, and every skin point keeps its distance from the centre.
TEST(Synth, FlatRotateSticksInTheCentreAndTurnsTheRimByTheTwist) {
  SceneSpec s = tiny("flat-rotate");
  s.frame_count = 21;
  const PointMm c = field_centre(s);
  const double theta = s.rotation_deg * std::numbers::pi / 180;
  for (int frame : {0, 5, 10, 20}) {
    const double twist = theta * (1 - std::cos(std::numbers::pi * frame / 20.0)) / 2;
    const PointMm stuck = skin_to_image(s, {c.x_mm + 1.0, c.y_mm - 0.8}, frame);
    EXPECT_NEAR(stuck.x_mm, c.x_mm + 1.0, 1e-12);
    EXPECT_NEAR(stuck.y_mm, c.y_mm - 0.8, 1e-12);
    const PointMm rim = skin_to_image(s, {c.x_mm + s.contact_semi_x_mm + 0.05, c.y_mm}, frame);
    const double r = s.contact_semi_x_mm + 0.05;
    EXPECT_NEAR(rim.x_mm, c.x_mm + r * std::cos(twist), 1e-9) << frame;
    EXPECT_NEAR(rim.y_mm, c.y_mm + r * std::sin(twist), 1e-9) << frame;
    const PointMm mid = skin_to_image(s, {c.x_mm + 2.0, c.y_mm + 2.5}, frame);
    EXPECT_NEAR(std::hypot(mid.x_mm - c.x_mm, mid.y_mm - c.y_mm), std::hypot(2.0, 2.5), 1e-9);
    const PointMm back = skin_to_image(s, image_to_skin(s, {c.x_mm + 3, c.y_mm - 1}, frame), frame);
    EXPECT_NEAR(back.x_mm, c.x_mm + 3, 1e-10);
    EXPECT_NEAR(back.y_mm, c.y_mm - 1, 1e-10);
  }
  // A radial image segment across the slip annulus at the last frame joins skin points turned by
  // different angles phi(r) = theta * smoothstep(q, 1, r / a): at frame 0 (no twist) that skin
  // is longer by the law of cosines.
  const double r1 = 2.6, r2 = 3.4;
  const double q = s.stick_ratio, a = s.contact_semi_x_mm;
  const double dphi = theta * (smoothstep(q, 1, r2 / a) - smoothstep(q, 1, r1 / a));
  const double expected =
      std::sqrt(r1 * r1 + r2 * r2 - 2 * r1 * r2 * std::cos(dphi)) / (r2 - r1) - 1;
  EXPECT_GT(expected, 0.005);
  EXPECT_NEAR(true_rel_change(s, {c.x_mm + r1, c.y_mm}, {c.x_mm + r2, c.y_mm}, 20, 0), expected,
              1e-9);
}

// Back-and-forth slide with a sticking centre: the rim follows U(t) = U sin(2 pi t / T) along x,
// the centre stays, nothing moves along y; the annulus stretches on the leading side and is
// compressed on the trailing side.
TEST(Synth, FlatStickSlipHoldsTheCentreAndSlidesTheRimBackAndForth) {
  SceneSpec s = tiny("flat-stick-slip");
  s.frame_count = 41;
  const PointMm c = field_centre(s);
  for (int frame : {0, 10, 20, 30, 40}) {
    const double u = s.lateral_amplitude_mm * std::sin(2 * std::numbers::pi * frame / 40.0);
    const PointMm stuck = skin_to_image(s, {c.x_mm - 1.2, c.y_mm + 1.0}, frame);
    EXPECT_NEAR(stuck.x_mm, c.x_mm - 1.2, 1e-12);
    EXPECT_NEAR(stuck.y_mm, c.y_mm + 1.0, 1e-12);
    const PointMm rim = skin_to_image(s, {c.x_mm, c.y_mm + s.contact_semi_y_mm + 0.1}, frame);
    EXPECT_NEAR(rim.x_mm, c.x_mm + u, 1e-9) << frame;
    EXPECT_NEAR(rim.y_mm, c.y_mm + s.contact_semi_y_mm + 0.1, 1e-12);
  }
  // At the peak (frame 10) in the middle of the annulus on the x axis, x = X + U s(rho(x)) gives
  // dX/dx = 1 - U s'(rho) / a with smoothstep's slope 1.5 / (1 - q) at its midpoint.
  const double q = s.stick_ratio, a = s.contact_semi_x_mm;
  const double slope = s.lateral_amplitude_mm * 1.5 / ((1 - q) * a);
  const double xm = (q + 1) / 2 * a;
  const double h = 0.001;
  const double leading =
      true_rel_change(s, {c.x_mm + xm - h, c.y_mm}, {c.x_mm + xm + h, c.y_mm}, 10, 0);
  const double trailing =
      true_rel_change(s, {c.x_mm - xm - h, c.y_mm}, {c.x_mm - xm + h, c.y_mm}, 10, 0);
  // From the peak back to rest: the leading side, stretched at the peak, shortens; the trailing
  // side lengthens.
  EXPECT_NEAR(leading, -slope, 1e-4);
  EXPECT_NEAR(trailing, slope, 1e-4);
  EXPECT_NEAR(true_rel_change(s, {c.x_mm + 0.5, c.y_mm}, {c.x_mm + 0.9, c.y_mm}, 10, 0), 0.0,
              1e-12);
}

TEST(Synth, PartialSlipScenesRenderLandmarksInContact) {
  for (const char* scene : {"flat-rotate", "flat-stick-slip"}) {
    const auto seq = render_sequence(tiny(scene));
    std::size_t at_last = 0;
    for (const auto& lm : seq.landmarks) {
      ASSERT_TRUE(in_contact(seq.spec, {lm.x_mm, lm.y_mm}, lm.frame));
      at_last += lm.frame == 3 ? 1 : 0;
    }
    EXPECT_GT(at_last, 150u) << scene;
  }
}

TEST(Synth, BadSpecIsRejectedWithTheFieldName) {
  // An unknown scene cannot be in a spec: its name is refused where it is parsed (above).
  SceneSpec s = tiny("bump");
  s.frame_rate_hz = 0;
  EXPECT_THAT([&] { render_sequence(s); }, ::testing::ThrowsMessage<std::invalid_argument>(
                                               ::testing::HasSubstr("frame_rate_hz")));
  s = tiny("flat-rotate");
  s.rotation_deg = 40;  // the slip field would fold the skin over itself
  EXPECT_THAT([&] { validate_scene(s); }, ::testing::ThrowsMessage<std::invalid_argument>(
                                              ::testing::HasSubstr("rotation_deg")));
  s = tiny("flat-stick-slip");
  s.stick_ratio = 0.95;
  EXPECT_THAT([&] { validate_scene(s); },
              ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("stick_ratio")));
}

}  // namespace
}  // namespace tactile::capture
