#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../../capture/src/pore_model.hpp"
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

// Scores every print, with the parameters `params_for` gives for it; prints per-image and
// overall figures.
template <class ParamsFor>
std::vector<Score> score_prints(const std::vector<Print>& prints, ParamsFor params_for,
                                const char* label, Score& total) {
  std::vector<Score> scores;
  for (std::size_t i = 0; i < prints.size(); ++i) {
    const Score s = score(extract_features(prints[i].image, kPxPerMm, params_for(i)),
                          prints[i].truth, 0.15 * kPxPerMm);
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
  score_prints(
      prints, [&](std::size_t) { return p; }, "paper rule", total);
  EXPECT_GT(double(total.matched) / total.truth, 0.2);
  EXPECT_LT(1.0 - double(total.matched) / total.found, 0.05);
}

FeatureParams ridge_blob_params() {
  FeatureParams p;
  p.pore_detector = PoreDetector::ridge_blob;
  p.find_minutiae = false;
  p.border_margin_mm = 0.0;
  return p;
}

std::vector<PoreTrainingPrint> training_prints(const std::vector<Print>& prints,
                                               std::size_t left_out) {
  std::vector<PoreTrainingPrint> out;
  for (std::size_t i = 0; i < prints.size(); ++i) {
    if (i != left_out) out.push_back({prints[i].image, prints[i].truth});
  }
  return out;
}

// The target, TDR >= 0.85 and FDR <= 0.15 with one-to-one mutual nearest neighbours
// within 0.15 mm, on every print and overall.
void expect_target(const std::vector<Score>& scores, const Score& total) {
  EXPECT_GE(double(total.matched) / total.truth, 0.85);
  EXPECT_LE(1.0 - double(total.matched) / total.found, 0.15);
  for (std::size_t i = 0; i < scores.size(); ++i) {
    EXPECT_GE(double(scores[i].matched) / scores[i].truth, 0.85) << "image " << i + 1;
    EXPECT_LE(1.0 - double(scores[i].matched) / scores[i].found, 0.15) << "image " << i + 1;
  }
}

// Held out: each print is scored with a pore model trained on the other 14 only, so these
// figures say how the detector does on a print it has not seen (the model's coefficients are
// fitted; the detector's other parameters were chosen on all 15, docs/capture-models.md 5b).
TEST(RealPores, RidgeBlobHeldOutOnPolyUHrf) {
  const auto prints = read_prints();
  std::vector<FeatureParams> params(prints.size(), ridge_blob_params());
  // Candidates do not depend on the model: found and labelled once per print.
  std::vector<LabelledCandidates> labelled;
  for (const auto& t : training_prints(prints, prints.size())) {
    labelled.push_back(label_pore_candidates(t, kPxPerMm, params[0].ridge_blob));
  }
  for (std::size_t i = 0; i < prints.size(); ++i) {
    std::vector<const LabelledCandidates*> others;
    for (std::size_t j = 0; j < prints.size(); ++j) {
      if (j != i) others.push_back(&labelled[j]);
    }
    params[i].ridge_blob.model = fit_pore_model(others);
  }
  Score total;
  const auto scores = score_prints(
      prints, [&](std::size_t i) { return params[i]; }, "held out", total);
  expect_target(scores, total);
}

// The shipped model (trained on all 15 prints): training figures, for the record and against
// regressions of the shipped detector.
TEST(RealPores, RidgeBlobDetectorOnPolyUHrf) {
  const auto prints = read_prints();
  Score total;
  const auto scores = score_prints(
      prints, [](std::size_t) { return ridge_blob_params(); }, "ridge blob", total);
  expect_target(scores, total);
}

// The committed coefficients are what the documented training gives on the 15 prints (not hand
// edits); after a change to the measures, this prints the table to paste into
// capture/src/pore_model_coefficients.cpp.
TEST(RealPores, ShippedPoreModelIsTrainedOnAllPrints) {
  const auto prints = read_prints();
  const auto trained = train_pore_model(training_prints(prints, prints.size()), kPxPerMm,
                                        ridge_blob_params().ridge_blob);
  const auto shipped = shipped_pore_model();
  ASSERT_EQ(trained.size(), shipped.size());
  bool same = true;
  for (std::size_t i = 0; i < trained.size(); ++i) {
    same = same && std::abs(trained[i] - shipped[i]) <= 1e-6 * (1.0 + std::abs(trained[i]));
  }
  if (!same) {
    for (double w : trained) std::printf("%.17g,\n", w);
  }
  EXPECT_TRUE(same) << "capture/src/pore_model_coefficients.cpp is out of date";
}

// Malformed input to the ridge-blob detector: no crash, no pores from nothing, a clear error
// for a model of the wrong size.
TEST(RealPores, RidgeBlobDetectorOnOddImages) {
  FeatureParams p = ridge_blob_params();
  for (const auto& [w, h] : {std::pair{1, 1}, {3, 3}, {5, 200}, {64, 48}}) {
    GrayImage flat{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h), 128)};
    EXPECT_TRUE(extract_features(flat, kPxPerMm, p).empty()) << w << " x " << h;
  }
  GrayImage noise{64, 48, std::vector<std::uint8_t>(64 * 48)};
  for (std::size_t i = 0; i < noise.pixels.size(); ++i) {
    noise.pixels[i] = static_cast<std::uint8_t>((i * 2654435761u) >> 24);
  }
  for (const auto& f : extract_features(noise, kPxPerMm, p)) {
    EXPECT_TRUE(f.x_px >= 0 && f.x_px < 64 && f.y_px >= 0 && f.y_px < 48);
  }
  p.ridge_blob.model = {1.0, 2.0};
  try {
    extract_features(noise, kPxPerMm, p);
    ADD_FAILURE() << "a 2-coefficient model was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("pore model has 2 coefficients"), std::string::npos);
  }
}

}  // namespace
}  // namespace tactile::capture
