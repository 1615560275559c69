#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "tactile/capture/features.hpp"
#include "tactile/capture/image.hpp"

namespace tactile::capture {
namespace {

struct Score {
  int truth = 0;
  int found = 0;
  int matched = 0;
};

// One-to-one pairing by mutual nearest neighbours within `bound_px` (the PolyU HRF convention).
Score score(const std::vector<Feature>& found, const std::vector<std::array<double, 2>>& truth,
            double bound_px) {
  auto nearest = [](double x, double y, const auto& pts, auto px, auto py) {
    std::size_t best = pts.size();
    double best_d = 1e30;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double d = std::hypot(px(pts[i]) - x, py(pts[i]) - y);
      if (d < best_d) {
        best_d = d;
        best = i;
      }
    }
    return std::pair{best, best_d};
  };
  auto fx = [](const Feature& f) { return f.x_px; };
  auto fy = [](const Feature& f) { return f.y_px; };
  auto tx = [](const std::array<double, 2>& t) { return t[0]; };
  auto ty = [](const std::array<double, 2>& t) { return t[1]; };
  Score s{static_cast<int>(truth.size()), static_cast<int>(found.size()), 0};
  for (std::size_t i = 0; i < found.size(); ++i) {
    const auto [t, d] = nearest(found[i].x_px, found[i].y_px, truth, tx, ty);
    if (t == truth.size() || d > bound_px) continue;
    const auto [back, d2] = nearest(truth[t][0], truth[t][1], found, fx, fy);
    if (back == i) ++s.matched;
  }
  return s;
}

struct Print {
  GrayImage image;
  std::vector<std::array<double, 2>> truth;  // x_px, y_px (0-based)
};

std::vector<Print> read_prints() {
  const std::filesystem::path dir =
      std::filesystem::path(TACTILE_SHARED_DATA_DIR) / "polyu-hrf-pores";
  std::vector<Print> prints;
  for (int n = 1; n <= 15; ++n) {
    char name[32];
    std::snprintf(name, sizeof name, "image_%02d.jpg", n);
    Print p{read_image(dir / name), {}};
    std::snprintf(name, sizeof name, "pores_%02d.txt", n);
    std::ifstream in(dir / name);
    for (double row, col; in >> row >> col;) p.truth.push_back({col - 1, row - 1});
    prints.push_back(std::move(p));
  }
  return prints;
}

constexpr double kPxPerMm = 47.0;

// Scores every print; prints per-image and overall figures.
std::vector<Score> score_prints(const std::vector<Print>& prints, const FeatureParams& p,
                                const char* label, Score& total) {
  std::vector<Score> scores;
  for (std::size_t i = 0; i < prints.size(); ++i) {
    const Score s =
        score(extract_features(prints[i].image, kPxPerMm, p), prints[i].truth, 0.15 * kPxPerMm);
    std::printf("%s image_%02zu: %d true, %d found, TDR %.3f, FDR %.3f\n", label, i + 1, s.truth,
                s.found, double(s.matched) / s.truth,
                1.0 - double(s.matched) / std::max(1, s.found));
    total.truth += s.truth;
    total.found += s.found;
    total.matched += s.matched;
    scores.push_back(s);
  }
  std::printf("%s overall: %d true, %d found, TDR %.3f, FDR %.3f\n", label, total.truth,
              total.found, double(total.matched) / total.truth,
              1.0 - double(total.matched) / std::max(1, total.found));
  return scores;
}

// The paper's pore rule on 15 real 1200 dpi prints with hand-marked pores: the baseline. It
// misses every pore that touches a valley (open pores merge into it), hence its low detection
// rate; what it does detect must be real pores.
TEST(RealPores, PaperRuleBaselineOnPolyUHrf) {
  const auto prints = read_prints();
  for (const auto& p : prints) ASSERT_GT(p.truth.size(), 300u);
  FeatureParams p;
  p.find_minutiae = false;
  p.border_margin_mm = 0.0;  // the ground truth covers the whole image
  Score total;
  score_prints(prints, p, "paper rule", total);
  EXPECT_GT(double(total.matched) / total.truth, 0.2);
  EXPECT_LT(1.0 - double(total.matched) / total.found, 0.05);
}

// The ridge-level detector against the target, TDR >= 0.85 and FDR <= 0.15 with
// one-to-one mutual nearest neighbours within 0.15 mm, overall and per image. Two prints are
// still short of it and are held to the figure they reach (so a regression there fails too):
// image 10, whose pores are small, packed 0.05-0.1 mm apart and often open at the ridge edge
// (TDR 0.78), and image 13, whose very dark, noisy ridges carry faint bright specks that are
// not marked as pores (FDR 0.17). docs/capture-models.md section 5b gives the figures.
TEST(RealPores, RidgeBlobDetectorOnPolyUHrf) {
  const auto prints = read_prints();
  FeatureParams p;
  p.pore_detector = PoreDetector::ridge_blob;
  p.find_minutiae = false;
  p.border_margin_mm = 0.0;
  Score total;
  const auto scores = score_prints(prints, p, "ridge blob", total);
  EXPECT_GE(double(total.matched) / total.truth, 0.85);
  EXPECT_LE(1.0 - double(total.matched) / total.found, 0.15);
  int within_target = 0;
  for (std::size_t i = 0; i < scores.size(); ++i) {
    const int image = static_cast<int>(i) + 1;
    const double tdr = double(scores[i].matched) / scores[i].truth;
    const double fdr = 1.0 - double(scores[i].matched) / scores[i].found;
    within_target += tdr >= 0.85 && fdr <= 0.15;
    EXPECT_GE(tdr, image == 10 ? 0.76 : 0.85) << "image " << image;
    EXPECT_LE(fdr, image == 13 ? 0.18 : 0.15) << "image " << image;
  }
  EXPECT_GE(within_target, 13);
}

}  // namespace
}  // namespace tactile::capture
