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

// The paper's pore rule on 15 real 1200 dpi prints with hand-marked pores. This is a baseline,
// not the goal: issue 3 asks for TDR >= 85 % and FDR <= 15 %. The rule misses every pore that
// touches a valley (open pores merge into it), hence its low detection rate; what it does
// detect must be real pores. Measured: 6599 true, 1818 detections, TDR 0.273, FDR 0.009.
TEST(RealPores, PaperRuleBaselineOnPolyUHrf) {
  const std::filesystem::path dir =
      std::filesystem::path(TACTILE_SHARED_DATA_DIR) / "polyu-hrf-pores";
  if (!std::filesystem::exists(dir / "image_01.jpg")) GTEST_SKIP() << "no data in " << dir;
  constexpr double kPxPerMm = 47.0;
  FeatureParams p;
  p.find_minutiae = false;
  p.border_margin_mm = 0.0;  // the ground truth covers the whole image
  Score total;
  for (int n = 1; n <= 15; ++n) {
    char name[32];
    std::snprintf(name, sizeof name, "image_%02d.jpg", n);
    const GrayImage img = read_image(dir / name);
    std::snprintf(name, sizeof name, "pores_%02d.txt", n);
    std::ifstream in(dir / name);
    std::vector<std::array<double, 2>> truth;
    for (double row, col; in >> row >> col;) truth.push_back({col - 1, row - 1});
    ASSERT_GT(truth.size(), 300u) << name;
    const Score s = score(extract_features(img, kPxPerMm, p), truth, 0.15 * kPxPerMm);
    total.truth += s.truth;
    total.found += s.found;
    total.matched += s.matched;
  }
  const double tdr = double(total.matched) / total.truth;
  const double fdr = 1.0 - double(total.matched) / std::max(1, total.found);
  std::printf("PolyU HRF, paper's rule: %d true pores, %d detections, TDR %.3f, FDR %.3f\n",
              total.truth, total.found, tdr, fdr);
  EXPECT_GT(tdr, 0.2);
  EXPECT_LT(fdr, 0.05);
}

}  // namespace
}  // namespace tactile::capture
