// Sub-pixel refinement of tracks against the images (refine_tracks), on a real print moved by an
// exact warp: the detections it starts from are the true positions plus noise, so what it adds
// is measured against the truth.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <stdexcept>

#include "tactile/capture/image.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/track.hpp"

namespace tactile::capture {
namespace {

namespace fs = std::filesystem;

struct Case {
  PrintSequence seq;
  std::vector<Track> truth;     // every mark in view in every frame, at its exact position
  std::vector<Track> detected;  // the same plus independent noise in every frame
};

Case make_case(WarpPattern pattern, double strain, double detection_noise_px) {
  const fs::path dir = fs::path(TACTILE_TEST_DATA_DIR) / "polyu-hrf-pores";
  const GrayImage print = read_image(dir / "image_12.jpg");
  const auto marks = read_pore_marks(dir / "pores_12.txt", print.width_px, print.height_px);
  PrintWarpSpec s;
  s.width_px = print.width_px;
  s.height_px = print.height_px;
  s.pattern = pattern;
  s.strain = strain;
  s.frame_count = 30;
  Case c;
  c.seq = render_print_sequence(s, print, marks);
  std::map<std::int32_t, Track> by_id;
  for (const auto& lm : c.seq.landmarks) {
    Track& t = by_id[lm.id];
    t.id = lm.id;
    t.x_px.push_back(lm.x_px);
    t.y_px.push_back(lm.y_px);
  }
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, detection_noise_px);
  for (auto& [id, t] : by_id) {
    if (static_cast<int>(t.x_px.size()) != s.frame_count) continue;  // left the view
    Track d = t;
    for (std::size_t k = 0; k < d.x_px.size(); ++k) {
      d.x_px[k] += noise(rng);
      d.y_px[k] += noise(rng);
    }
    c.truth.push_back(t);
    c.detected.push_back(d);
  }
  return c;
}

// RMS over tracks and frames of the error of each track's motion since its first frame (a
// constant offset of a whole track does not change any strain).
double motion_error_px(const std::vector<Track>& measured, const std::vector<Track>& truth) {
  double se = 0;
  long n = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    for (std::size_t k = 1; k < truth[i].x_px.size(); ++k) {
      const double ex =
          (measured[i].x_px[k] - measured[i].x_px[0]) - (truth[i].x_px[k] - truth[i].x_px[0]);
      const double ey =
          (measured[i].y_px[k] - measured[i].y_px[0]) - (truth[i].y_px[k] - truth[i].y_px[0]);
      se += ex * ex + ey * ey;
      ++n;
    }
  }
  return std::sqrt(se / static_cast<double>(n));
}

TEST(RefineTracks, RecoversTheExactMotionFromNoisyDetections) {
  // Slide and rotation (which an affine window follows exactly), with the camera's noise, blur
  // and drift; detections 0.5 px off at random in every frame.
  Case c = make_case(WarpPattern::rigid, 0.0, 0.5);
  ASSERT_GT(c.truth.size(), 100u);
  std::vector<Track> refined = c.detected;
  const RefineStats stats = refine_tracks(c.seq.frames, refined, c.seq.spec.px_per_mm);
  std::vector<double> before, after;
  for (std::size_t i = 0; i < refined.size(); ++i) {
    before.push_back(motion_error_px({c.detected[i]}, {c.truth[i]}));
    after.push_back(motion_error_px({refined[i]}, {c.truth[i]}));
  }
  std::sort(before.begin(), before.end());
  std::sort(after.begin(), after.end());
  const auto quantile = [](const std::vector<double>& v, double q) {
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
  };
  // Two noisy positions per motion: 0.5 px x sqrt(2) per axis, sqrt(2) for both axes.
  EXPECT_NEAR(quantile(before, 0.5), 1.0, 0.1);
  // The image gives motions ten times better than the detections for nine tracks in ten, and
  // twenty times better for half.
  EXPECT_LT(quantile(after, 0.9), 0.1);
  EXPECT_LT(quantile(after, 0.5), 0.05);
  std::printf("motion error per track: median %.4f px, 90th percentile %.4f px (detections %.3f)\n",
              quantile(after, 0.5), quantile(after, 0.9), quantile(before, 0.5));
  EXPECT_EQ(stats.steps, static_cast<long>(c.truth.size()) * 29);
  EXPECT_LT(stats.rejected, stats.steps / 20);
}

TEST(RefineTracks, AStepTheImageCannotConfirmKeepsTheDetectedStep) {
  Case c = make_case(WarpPattern::rigid, 0.0, 0.3);
  ASSERT_FALSE(c.truth.empty());
  // One track's detections jump 10 px in frame 10 (another pore taken for it): beyond the
  // largest offset of a confirmed position, so the refined track follows its detections there.
  std::vector<Track> refined = {c.detected[0]};
  for (std::size_t k = 10; k < refined[0].x_px.size(); ++k) refined[0].x_px[k] += 10.0;
  const Track detected = refined[0];
  const RefineStats stats = refine_tracks(c.seq.frames, refined, c.seq.spec.px_per_mm);
  EXPECT_GE(stats.rejected, 1);
  EXPECT_NEAR(refined[0].x_px[10] - refined[0].x_px[9], detected.x_px[10] - detected.x_px[9], 1e-9);
  for (std::size_t k = 0; k < refined[0].x_px.size(); ++k) {
    EXPECT_TRUE(std::isfinite(refined[0].x_px[k]) && std::isfinite(refined[0].y_px[k]));
  }
}

TEST(RefineTracks, TracksAtTheBorderAreRefinedOrLeftAsDetected) {
  Case c = make_case(WarpPattern::rigid, 0.0, 0.3);
  // A landmark on the very edge of the frames, and one that moves out of them.
  Track edge;
  edge.x_px.assign(30, 0.0);
  edge.y_px.assign(30, 120.0);
  Track leaving;
  for (int k = 0; k < 30; ++k) {
    leaving.x_px.push_back(300.0 + k);
    leaving.y_px.push_back(100.0);
  }
  std::vector<Track> tracks = {edge, leaving};
  const RefineStats stats = refine_tracks(c.seq.frames, tracks, c.seq.spec.px_per_mm);
  EXPECT_EQ(stats.steps, 58);
  for (const auto& t : tracks) {
    for (std::size_t k = 0; k < t.x_px.size(); ++k) {
      EXPECT_TRUE(std::isfinite(t.x_px[k]) && std::isfinite(t.y_px[k]));
    }
  }
  EXPECT_GT(stats.rejected, 0);  // the one that leaves
}

TEST(RefineTracks, BadArgumentsAreRefused) {
  Case c = make_case(WarpPattern::rigid, 0.0, 0.3);
  std::vector<Track> tracks = {c.detected[0]};
  EXPECT_THROW(refine_tracks(c.seq.frames, tracks, 0.0), std::invalid_argument);
  RefineParams p;
  p.window_mm = 0;
  EXPECT_THROW(refine_tracks(c.seq.frames, tracks, 47, p), std::invalid_argument);
  p = {};
  p.min_correlation = 1.5;
  EXPECT_THROW(refine_tracks(c.seq.frames, tracks, 47, p), std::invalid_argument);
  tracks[0].first_frame = 5;  // its 30 positions reach frame 34 of 30
  EXPECT_THROW(refine_tracks(c.seq.frames, tracks, 47), std::invalid_argument);
}

}  // namespace
}  // namespace tactile::capture
