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
#include <utility>

#include "real_prints.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/track.hpp"

namespace tactile::capture {
namespace {

struct Case {
  PrintSequence seq;
  std::vector<Track> truth;     // every mark in view in every frame, at its exact position
  std::vector<Track> detected;  // the same plus independent noise in every frame
};

Case make_case(WarpPattern pattern, double strain, double detection_noise_px) {
  const GrayImage print = read_image(test::print_path("12", "image_"));
  const auto marks =
      read_pore_marks(test::print_path("12", "pores_"), print.width_px, print.height_px);
  const PrintWarpSpec s = test::spec_for(print, pattern, strain);
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

// The tracks nearest the frame's centre, nearest first (their windows stay inside the frames).
std::vector<std::size_t> central(const Case& c) {
  std::vector<std::size_t> order(c.truth.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  const auto distance = [&](std::size_t i) {
    return std::hypot(c.truth[i].x_px[0] - c.seq.spec.width_px / 2.0,
                      c.truth[i].y_px[0] - c.seq.spec.height_px / 2.0);
  };
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return distance(a) < distance(b); });
  return order;
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

// Each refined track's motion error against its truth, over the frames it kept. A refined track
// starts at its detection (its reference), which finds its truth again: the refinement drops and
// renumbers the tracks it cannot confirm.
std::vector<double> refined_motion_errors_px(const Case& c, const std::vector<Track>& refined) {
  std::map<std::pair<double, double>, std::size_t> by_start;
  for (std::size_t i = 0; i < c.detected.size(); ++i) {
    by_start[{c.detected[i].x_px[0], c.detected[i].y_px[0]}] = i;
  }
  std::vector<double> errors;
  for (const auto& r : refined) {
    const auto it = by_start.find({r.x_px[0], r.y_px[0]});
    if (it == by_start.end()) throw std::logic_error("a refined track starts at no detection");
    Track truth = c.truth[it->second];
    truth.x_px.resize(r.x_px.size());
    truth.y_px.resize(r.y_px.size());
    errors.push_back(motion_error_px({r}, {truth}));
  }
  return errors;
}

double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

double rms(const std::vector<double>& v) {
  double s = 0;
  for (const double x : v) s += x * x;
  return std::sqrt(s / static_cast<double>(v.size()));
}

TEST(RefineTracks, RecoversTheExactMotionFromNoisyDetections) {
  // Slide and rotation (which an affine window follows exactly), with the camera's noise, blur
  // and drift; detections 0.5 px off at random in every frame.
  Case c = make_case(WarpPattern::rigid, 0.0, 0.5);
  ASSERT_GT(c.truth.size(), 100u);
  std::vector<Track> refined = c.detected;
  const RefineStats stats = refine_tracks(c.seq.frames, refined, c.seq.spec.px_per_mm);
  std::vector<double> before;
  for (const auto& d : c.detected)
    before.push_back(motion_error_px({d}, {c.truth[&d - &c.detected[0]]}));
  std::vector<double> after = refined_motion_errors_px(c, refined);
  ASSERT_GT(after.size(), c.truth.size() * 9 / 10);
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
  EXPECT_LT(stats.cut, static_cast<long>(c.truth.size()) / 10);
}

TEST(RefineTracks, AlternatingRowHalvesAreAsPreciseAsWholeWindows) {
  // The alignment's steps alternate between the even and the odd rows of each window. A track
  // that ended on the last half step's warp alone (one half's fixed point) came out 6-7 % further
  // from the truth here than whole-window alignment: neighbouring rows share much of their noise
  // through the presmoothing, but not all of it. Ending on the mean of the two halves must keep
  // the whole window's precision, to within half of that. A slide and rotation, which the affine
  // window follows exactly, with the camera's noise.
  Case c = make_case(WarpPattern::rigid, 0.0, 0.3);
  ASSERT_GT(c.truth.size(), 100u);
  RefineParams halves, whole;
  halves.alternate_row_halves = true;
  whole.alternate_row_halves = false;
  std::vector<Track> by_halves = c.detected, by_whole = c.detected;
  refine_tracks(c.seq.frames, by_halves, c.seq.spec.px_per_mm, halves);
  refine_tracks(c.seq.frames, by_whole, c.seq.spec.px_per_mm, whole);
  ASSERT_GT(by_halves.size(), c.truth.size() * 9 / 10);
  ASSERT_GT(by_whole.size(), c.truth.size() * 9 / 10);
  const std::vector<double> error_halves = refined_motion_errors_px(c, by_halves);
  const std::vector<double> error_whole = refined_motion_errors_px(c, by_whole);
  std::printf(
      "motion error per track, alternating halves / whole windows: median %.5f / %.5f px, "
      "RMS %.5f / %.5f px\n",
      median_of(error_halves), median_of(error_whole), rms(error_halves), rms(error_whole));
  EXPECT_LT(median_of(error_halves), 1.03 * median_of(error_whole));
  EXPECT_LT(rms(error_halves), 1.03 * rms(error_whole));
}

TEST(RefineTracks, WindowsCutByTheFrameBorderFollowTheMotionToo) {
  // Landmarks whose window (0.8 mm, 39 px, by default) reaches past the frame's border: their
  // references are cut to the part inside, and the slide carries some of them further out, so
  // the alignment sums over a window cut differently at every step.
  Case c = make_case(WarpPattern::rigid, 0.0, 0.5);
  const int w = c.seq.spec.width_px, h = c.seq.spec.height_px;
  const double half_side_px = RefineParams{}.window_mm * c.seq.spec.px_per_mm / 2;
  std::vector<Track> near_border, truth;
  for (std::size_t i = 0; i < c.truth.size(); ++i) {
    const double x = c.truth[i].x_px[0], y = c.truth[i].y_px[0];
    if (std::min({x, y, w - 1 - x, h - 1 - y}) < half_side_px) {
      near_border.push_back(c.detected[i]);
      truth.push_back(c.truth[i]);
    }
  }
  ASSERT_GE(near_border.size(), 20u);
  std::map<std::pair<double, double>, std::size_t> by_start;
  for (std::size_t i = 0; i < near_border.size(); ++i) {
    by_start[{near_border[i].x_px[0], near_border[i].y_px[0]}] = i;
  }
  std::vector<Track> refined = near_border;
  refine_tracks(c.seq.frames, refined, c.seq.spec.px_per_mm);
  // The goals for whole windows above, the 90th percentile's doubled: a window cut to a quarter
  // of its pixels (the least a reference keeps) averages its noise over a quarter of them.
  EXPECT_GE(refined.size(), near_border.size() * 3 / 4);
  std::vector<double> after;
  for (const auto& r : refined) {
    const auto it = by_start.find({r.x_px[0], r.y_px[0]});
    ASSERT_NE(it, by_start.end());
    Track t = truth[it->second];
    t.x_px.resize(r.x_px.size());
    t.y_px.resize(r.y_px.size());
    after.push_back(motion_error_px({r}, {t}));
  }
  std::sort(after.begin(), after.end());
  EXPECT_LT(after[after.size() / 2], 0.05);
  EXPECT_LT(after[after.size() * 9 / 10], 0.2);
  std::printf("%zu of %zu windows at the border kept; motion error median %.4f px\n",
              refined.size(), near_border.size(), after[after.size() / 2]);
}

TEST(RefineTracks, ATrackEndsWhereTheImageCannotConfirmIt) {
  Case c = make_case(WarpPattern::rigid, 0.0, 0.3);
  ASSERT_GE(c.truth.size(), 2u);
  // One track's detections jump 10 px in frame 15 (another pore taken for it): beyond the
  // largest offset of a confirmed position, so the track ends at frame 14.
  const auto order = central(c);
  const std::size_t a = order[0], b = order[1];
  std::vector<Track> tracks = {c.detected[a], c.detected[b]};
  for (std::size_t k = 15; k < tracks[0].x_px.size(); ++k) tracks[0].x_px[k] += 10.0;
  const RefineStats stats = refine_tracks(c.seq.frames, tracks, c.seq.spec.px_per_mm);
  ASSERT_EQ(tracks.size(), 2u);
  EXPECT_EQ(tracks[0].last_frame(), 14);
  EXPECT_EQ(tracks[1].last_frame(), 29);
  EXPECT_EQ(stats.cut, 1);
  EXPECT_EQ(stats.dropped, 0);
  for (std::size_t k = 1; k < tracks[0].x_px.size(); ++k) {
    const double step = tracks[0].x_px[k] - tracks[0].x_px[k - 1];
    const double truth = c.truth[a].x_px[k] - c.truth[a].x_px[k - 1];
    EXPECT_NEAR(step, truth, 0.1) << "frame " << k;
  }
}

TEST(RefineTracks, TracksWithoutEnoughConfirmedFramesAreDroppedAndTheRestRenumbered) {
  Case c = make_case(WarpPattern::rigid, 0.0, 0.3);
  // A landmark outside the frames (no reference), one whose detections jump at frame 5 (fewer
  // than min_frames confirmed), and a good one.
  Track outside;
  outside.id = 7;
  outside.x_px.assign(30, -40.0);
  outside.y_px.assign(30, 120.0);
  const auto order = central(c);
  Track jumping = c.detected[order[0]];
  jumping.id = 8;
  for (std::size_t k = 5; k < jumping.x_px.size(); ++k) jumping.y_px[k] += 12.0;
  Track good = c.detected[order[1]];
  good.id = 9;
  std::vector<Track> tracks = {outside, jumping, good};
  const RefineStats stats = refine_tracks(c.seq.frames, tracks, c.seq.spec.px_per_mm);
  ASSERT_EQ(tracks.size(), 1u);
  EXPECT_EQ(tracks[0].id, 0);
  EXPECT_EQ(tracks[0].x_px.size(), 30u);
  EXPECT_NEAR(tracks[0].x_px[29] - tracks[0].x_px[0],
              c.truth[order[1]].x_px[29] - c.truth[order[1]].x_px[0], 0.1);
  EXPECT_EQ(stats.cut, 2);
  EXPECT_EQ(stats.dropped, 2);
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
  p = {};
  p.min_frames = 1;
  EXPECT_THROW(refine_tracks(c.seq.frames, tracks, 47, p), std::invalid_argument);
  tracks[0].first_frame = 5;  // its 30 positions reach frame 34 of 30
  EXPECT_THROW(refine_tracks(c.seq.frames, tracks, 47), std::invalid_argument);
}

}  // namespace
}  // namespace tactile::capture
