#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "tactile/capture/features.hpp"
#include "tactile/capture/synth.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

// A dark "ridge" field with one bright disk: the paper's rule must find exactly one pore, at the
// disk's centre, to a fraction of a pixel (the disk is drawn with exact area coverage).
TEST(Features, FindsOneDiskPoreAtItsSubPixelCentre) {
  const int w = 200, h = 160;
  const double cx = 104.3, cy = 81.6, r = 4.0;  // inside a dark stripe
  GrayImage img{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h))};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      int inside = 0;
      for (int s = 0; s < 16; ++s) {
        const double dx = x - 0.5 + (s % 4 + 0.5) / 4 - cx;
        const double dy = y - 0.5 + (s / 4 + 0.5) / 4 - cy;
        inside += dx * dx + dy * dy < r * r;
      }
      // Stripes keep the local contrast high so the field is not taken for background.
      const double base = (x / 14) % 2 == 0 ? 60 : 50;
      img.pixels[static_cast<std::size_t>(y * w + x)] =
          static_cast<std::uint8_t>(base + (180 - base) * inside / 16.0);
    }
  }
  FeatureParams p;
  p.background_max_std = 1.0;
  p.find_minutiae = false;
  const auto f = extract_features(img, 60.0, p);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].type, FeatureType::pore);
  EXPECT_NEAR(f[0].x_px, cx, 0.15);
  EXPECT_NEAR(f[0].y_px, cy, 0.15);
}

// Against the renderer's ground truth: detected pores are real (within 0.1 mm of a true pore),
// most true pores are found, and their positions are sub-pixel. Measured for this frame:
// see the printed figures; the paper's rule misses pores that touch a valley (they merge with
// it), so recall is well below 100 % by design of this first version.
TEST(Features, PoresOnASyntheticFrameMatchTheGroundTruth) {
  SceneSpec spec;
  spec.frame_count = 1;
  const auto seq = render_sequence(spec);
  FeatureParams p;
  p.find_minutiae = false;
  const auto found = extract_features(seq.frames[0], 1.0 / seq.calibration.mm_per_px, p);
  const double tol_px = 0.1 / seq.calibration.mm_per_px;
  int truth = 0, hit = 0;
  double se = 0;
  for (const auto& lm : seq.landmarks) {
    if (lm.type != FeatureType::pore) continue;
    ++truth;
    double best = 1e9;
    for (const auto& f : found)
      best = std::min(best, std::hypot(f.x_px - lm.x_px, f.y_px - lm.y_px));
    if (best < tol_px) {
      ++hit;
      se += best * best;
    }
  }
  int false_pores = 0;
  for (const auto& f : found) {
    double best = 1e9;
    for (const auto& lm : seq.landmarks)
      best = std::min(best, std::hypot(f.x_px - lm.x_px, f.y_px - lm.y_px));
    false_pores += best >= tol_px;
  }
  std::printf("pores: %d true, %d found, %d false, RMS %.3f px\n", truth, hit, false_pores,
              std::sqrt(se / hit));
  ASSERT_GT(truth, 100);
  EXPECT_GT(hit, truth / 2) << hit << " of " << truth;
  EXPECT_LT(false_pores, static_cast<int>(found.size()) / 20 + 1);
  EXPECT_LT(std::sqrt(se / hit), 0.3) << "pore localisation RMS error in px";
}

// Minutiae on a synthetic frame against the rendered ones (phase singularities; the skeleton's
// end lies up to about 0.15 mm from them, hence a 0.25 mm tolerance). Most true minutiae must be
// found, with at most 2.5 reports per true one: without the syntactic repair of the skeleton,
// spurs and bridges made about 3.5 (32 for 9 on this frame).
TEST(Features, MinutiaeOnASyntheticFrameAreMostlyTrueOnes) {
  SceneSpec spec;
  spec.frame_count = 1;
  const auto seq = render_sequence(spec);
  const double px_per_mm = 1.0 / seq.calibration.mm_per_px;
  const auto found = extract_features(seq.frames[0], px_per_mm, FeatureParams{});
  const double tol_px = 0.25 * px_per_mm;
  int truth = 0, reported = 0, true_found = 0;
  for (const auto& lm : seq.landmarks) {
    if (lm.type == FeatureType::pore) continue;
    ++truth;
    for (const auto& f : found) {
      if (f.type == lm.type && std::hypot(f.x_px - lm.x_px, f.y_px - lm.y_px) < tol_px) {
        ++true_found;
        break;
      }
    }
  }
  for (const auto& f : found) reported += f.type != FeatureType::pore;
  std::printf("minutiae: %d true, %d reported, %d true ones found\n", truth, reported, true_found);
  ASSERT_GT(truth, 0);
  EXPECT_GE(true_found, truth / 2);
  EXPECT_LE(2 * reported, 5 * truth);
}

TEST(Features, CsvHasTheDocumentedHeaderAndOneRowPerFeature) {
  testing::TempDir dir;
  const std::vector<Feature> f{{FeatureType::pore, 10, 20, 0}, {FeatureType::ending, 30, 5, 1.5}};
  const Calibration cal = uniform_calibration(50.0, 100, 100);
  write_features_csv(dir.path() / "f.csv", f, cal);
  std::ifstream in(dir.path() / "f.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "type,x_px,y_px,x_mm,y_mm,orientation_rad");
  std::getline(in, line);
  EXPECT_EQ(line, "pore,10.0000,20.0000,0.20000,0.40000,0.00000");
  std::getline(in, line);
  EXPECT_EQ(line, "ending,30.0000,5.0000,0.60000,0.10000,1.50000");
}

TEST(Features, UniformImageHasNoFeatures) {
  GrayImage flat{120, 90, std::vector<std::uint8_t>(120 * 90, 200)};
  EXPECT_TRUE(extract_features(flat, 60.0).empty());
}

}  // namespace
}  // namespace tactile::capture
