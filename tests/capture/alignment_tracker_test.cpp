// The streaming tracker (AlignmentTracker) given seeds found on an earlier frame, as the live
// session's detector, slower than the camera, hands them over: on a real print crossed by a fast
// strain wave, where the skin under each seed has moved pixels away from where the view's median
// motion puts it.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "real_prints.hpp"
#include "tactile/capture/bench.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/capture/track.hpp"
#include "tactile/common/stats.hpp"

namespace tactile::capture {
namespace {

struct Scene {
  PrintSequence seq;
  // Each mark in view in every frame, by id: its exact position frame by frame.
  std::map<std::int32_t, std::vector<TruthLandmark>> marks;
};

Scene fast_wave(int frames) {
  const GrayImage print = read_image(test::print_path("12", "image_"));
  const auto marks =
      read_pore_marks(test::print_path("12", "pores_"), print.width_px, print.height_px);
  PrintWarpSpec spec = test::spec_for(print, WarpPattern::wave, 0.08);
  spec.frame_count = frames;
  set_fast_scene(spec, 25);
  Scene s;
  s.seq = render_print_sequence(spec, print, marks);
  for (const auto& lm : s.seq.landmarks) s.marks[lm.id].push_back(lm);
  std::erase_if(s.marks, [&](const auto& m) { return static_cast<int>(m.second.size()) < frames; });
  return s;
}

// The marks with ids in [first, end) of `by`, where they are in `frame`, as pore seeds.
std::vector<Feature> seeds_at(const Scene& s, int frame, std::size_t first, std::size_t end) {
  std::vector<Feature> out;
  std::size_t k = 0;
  for (const auto& [id, path] : s.marks) {
    if (k >= first && k < end) {
      Feature f;
      f.type = FeatureType::pore;
      f.x_px = path[static_cast<std::size_t>(frame)].x_px;
      f.y_px = path[static_cast<std::size_t>(frame)].y_px;
      out.push_back(f);
    }
    ++k;
  }
  return out;
}

// Skin around the marks: a grid every 16 px (a window tracks whatever texture it holds), clear of
// the marks by 6 px, as a detector's dense landmarks surround the ones it finds late.
std::vector<Feature> grid_clear_of_marks(const Scene& s) {
  std::vector<Feature> out;
  const GrayImage& f0 = s.seq.frames[0];
  for (int y = 16; y < f0.height_px - 16; y += 16) {
    for (int x = 16; x < f0.width_px - 16; x += 16) {
      bool clear = true;
      for (const auto& [id, path] : s.marks) {
        clear = clear && std::hypot(path[0].x_px - x, path[0].y_px - y) > 6;
      }
      if (!clear) continue;
      Feature f;
      f.x_px = x;
      f.y_px = y;
      out.push_back(f);
    }
  }
  return out;
}

TEST(AlignmentTracker, SeedsFromAnEarlierFrameLandOnTheSkinTheyWereFoundOn) {
  constexpr int kFrames = 14, kFoundOn = 6, kHandedOver = 11;
  const Scene s = fast_wave(kFrames);
  ASSERT_GE(s.marks.size(), 40u);
  const std::size_t half = s.marks.size() / 2;
  RefineParams params;
  params.min_frames = 2;
  const double separation_px = 0.5 * params.max_offset_mm / s.seq.calibration.mm_per_px;

  // The scene is one where the view's median motion since the seeds' frame misplaces seeds:
  // a seed moved by it lands further from its own skin than the tracker's separation of one
  // landmark from another.
  std::vector<double> dx, dy;
  for (const auto& [id, path] : s.marks) {
    dx.push_back(path[kHandedOver].x_px - path[kFoundOn].x_px);
    dy.push_back(path[kHandedOver].y_px - path[kFoundOn].y_px);
  }
  const double mx = median(dx), my = median(dy);
  int misplaced = 0;
  for (std::size_t i = 0; i < dx.size(); ++i) {
    misplaced += std::hypot(dx[i] - mx, dy[i] - my) > separation_px;
  }
  ASSERT_GT(misplaced, static_cast<int>(dx.size()) / 10)
      << "the wave does not move the skin away from the median motion";

  AlignmentTracker tracker(1.0 / s.seq.calibration.mm_per_px, params, 2);
  for (int f = 0; f < kFrames; ++f) {
    if (f == 0) {
      std::vector<Feature> seeds = grid_clear_of_marks(s);
      const auto marked = seeds_at(s, 0, 0, half);
      seeds.insert(seeds.end(), marked.begin(), marked.end());
      tracker.add_frame(s.seq.frames[0], seeds);
    } else if (f == kHandedOver) {
      // Every mark, as found on frame kFoundOn: the first half are tracked already.
      const int before = tracker.live_tracks();
      tracker.add_frame(s.seq.frames[f], seeds_at(s, kFoundOn, 0, s.marks.size()), kFoundOn);
      const int started = tracker.live_tracks() - before;
      EXPECT_LE(started, static_cast<int>(s.marks.size() - half))
          << "a seed on skin already tracked started a second track";
      EXPECT_GE(started, static_cast<int>(9 * (s.marks.size() - half) / 10))
          << "the untracked marks did not start tracks";
    } else {
      tracker.add_frame(s.seq.frames[f], {});
    }
  }
  const std::vector<Track> tracks = tracker.finish();
  // Each track begun on the hand-over frame starts where its mark is on that frame.
  std::vector<double> start_error_px;
  for (const auto& t : tracks) {
    if (t.first_frame != kHandedOver) continue;
    double nearest = INFINITY;
    for (const auto& [id, path] : s.marks) {
      nearest = std::min(nearest, std::hypot(t.x_px[0] - path[kHandedOver].x_px,
                                             t.y_px[0] - path[kHandedOver].y_px));
    }
    start_error_px.push_back(nearest);
  }
  ASSERT_FALSE(start_error_px.empty());
  EXPECT_LT(median(start_error_px), 0.5);
  EXPECT_LT(quantile(start_error_px, 0.9), separation_px);
}

TEST(AlignmentTracker, SeedsFromAFrameNotYetSeenOrBeforeTheFirstAreRefused) {
  const Scene s = fast_wave(3);
  AlignmentTracker tracker(1.0 / s.seq.calibration.mm_per_px);
  tracker.add_frame(s.seq.frames[0], seeds_at(s, 0, 0, 10));
  for (const int bad : {-1, 2, 100}) {
    try {
      tracker.add_frame(s.seq.frames[1], seeds_at(s, 0, 0, 10), bad);
      ADD_FAILURE() << "seeds of frame " << bad << " taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("frame " + std::to_string(bad)), std::string::npos)
          << e.what();
    }
  }
  // Refused before anything changed: the next frame is still frame 1.
  EXPECT_EQ(tracker.frames(), 1);
  EXPECT_NO_THROW(tracker.add_frame(s.seq.frames[1], seeds_at(s, 0, 0, 10), 0));
  EXPECT_EQ(tracker.frames(), 2);
}

// The least distance between the live tracks' last positions (px).
double least_distance(const std::vector<Track>& steps) {
  double least = 1e300;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    for (std::size_t j = i + 1; j < steps.size(); ++j) {
      least = std::min(least, std::hypot(steps[i].x_px[1] - steps[j].x_px[1],
                                         steps[i].y_px[1] - steps[j].y_px[1]));
    }
  }
  return least;
}

TEST(AlignmentTracker, ASpacingEndsTracksThatCrowdOlderOnesAndStartsNoneWithinIt) {
  const Scene s = fast_wave(5);
  // Seeds every 16 px; a spacing of 40 px keeps at most one in two along each axis.
  const std::vector<Feature> grid = grid_clear_of_marks(s);
  AlignmentTracker dense(1.0 / s.seq.calibration.mm_per_px);
  AlignmentTracker spaced(1.0 / s.seq.calibration.mm_per_px);
  dense.add_frame(s.seq.frames[0], grid);
  spaced.add_frame(s.seq.frames[0], grid);
  dense.add_frame(s.seq.frames[1], {});
  spaced.add_frame(s.seq.frames[1], {});
  const int before = spaced.live_tracks();
  ASSERT_GT(before, 50);
  EXPECT_EQ(before, dense.live_tracks());
  EXPECT_LT(least_distance(spaced.last_step()), 20);
  // From the next frame on: the crowded tracks end, the seeds within the spacing start none.
  spaced.set_min_spacing_px(40);
  spaced.add_frame(s.seq.frames[2], grid);
  const std::vector<Track> steps = spaced.last_step();
  EXPECT_GE(least_distance(steps), 40);
  EXPECT_LT(spaced.live_tracks(), before / 2);
  EXPECT_GT(spaced.live_tracks(), before / 8);  // a grid 40 px apart still, not an empty view
  // Every survivor is an older track, where the dense tracker has it: to within the correction
  // of the window's curvature, which reads the neighbours' motion and so changes as they thin.
  dense.add_frame(s.seq.frames[2], {});
  std::map<std::int32_t, Track> by_id;
  for (const auto& t : dense.last_step()) by_id[t.id] = t;
  for (const auto& t : steps) {
    ASSERT_TRUE(by_id.count(t.id)) << "track " << t.id << " is not one of the first frame's";
    EXPECT_NEAR(t.x_px[1], by_id[t.id].x_px[1], 0.5) << "track " << t.id;
    EXPECT_NEAR(t.y_px[1], by_id[t.id].y_px[1], 0.5) << "track " << t.id;
  }
  // A seed far off any frame (as no detector gives) is not started, and breaks nothing.
  const int spaced_tracks = spaced.live_tracks();
  Feature far;
  far.x_px = far.y_px = 1e300;
  spaced.add_frame(s.seq.frames[3], {far});
  EXPECT_LE(spaced.live_tracks(), spaced_tracks);
  // Back to every landmark: the seeds start tracks between the spaced ones again.
  spaced.set_min_spacing_px(0);
  spaced.add_frame(s.seq.frames[4], grid);
  EXPECT_GT(spaced.live_tracks(), static_cast<int>(steps.size()));
}

TEST(AlignmentTracker, ASpacingThatIsNoDistanceIsRefused) {
  AlignmentTracker tracker(47);
  for (const double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    try {
      tracker.set_min_spacing_px(bad);
      ADD_FAILURE() << "spacing " << bad << " taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("is not a distance"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace tactile::capture
