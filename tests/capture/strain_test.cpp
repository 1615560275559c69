#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <stdexcept>
#include <tuple>

#include <Eigen/Dense>

#include "tactile/capture/capture.hpp"
#include "tactile/capture/synth.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

std::vector<TrackedPoint> grid_points(int n, double pitch_mm) {
  std::vector<TrackedPoint> pts;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      // A slight shear avoids the co-circular ties of a perfect square lattice; 1/16 keeps the
      // coordinates exact in binary so that the border points stay exactly collinear.
      const double x = i * pitch_mm + 0.0625 * j * pitch_mm;
      const double y = j * pitch_mm;
      pts.push_back(
          {static_cast<std::int32_t>(100 + pts.size()), 0, FeatureType::pore, 0, 0, x, y});
    }
  }
  return pts;
}

// A movie's edges against the exact relative length change of the same skin segments
// (true_rel_change maps both ends through the scene's skin model).
struct EdgeErrors {
  double rms_error = 0;
  double rms_truth = 0;
  long edges = 0;
  std::size_t median_points = 0;
};

EdgeErrors edge_errors(const StrainMovie& movie, const SceneSpec& spec) {
  EdgeErrors e;
  double se = 0, st = 0;
  std::vector<std::size_t> counts;
  for (const auto& f : movie.frames) {
    counts.push_back(f.points_from.size());
    std::map<std::int32_t, TrackedPoint> at;
    for (const auto& pt : f.points_from) at[pt.track_id] = pt;
    for (const auto& edge : f.edges) {
      const auto& a = at.at(edge.track_a);
      const auto& b = at.at(edge.track_b);
      const double truth =
          true_rel_change(spec, {a.x_mm, a.y_mm}, {b.x_mm, b.y_mm}, f.frame_from, f.frame_to);
      se += (edge.rel_change - truth) * (edge.rel_change - truth);
      st += truth * truth;
      ++e.edges;
    }
  }
  if (e.edges == 0 || counts.empty()) return e;
  std::sort(counts.begin(), counts.end());
  e.median_points = counts[counts.size() / 2];
  e.rms_error = std::sqrt(se / static_cast<double>(e.edges));
  e.rms_truth = std::sqrt(st / static_cast<double>(e.edges));
  return e;
}

TEST(Strain, UniformScalingGivesThatStrainOnEveryEdge) {
  const auto from = grid_points(6, 0.5);
  auto to = from;
  for (auto& p : to) {
    p.x_mm = 1.0 + 1.05 * p.x_mm;  // translation must not matter, scale must
    p.y_mm = -2.0 + 1.05 * p.y_mm;
  }
  std::vector<StrainEdge> edges;
  std::vector<StrainTriangle> triangles;
  triangulate_strain(from, to, 3.0, edges, triangles);
  // A triangulation of V points with H on the hull has 3V - 3 - H edges and 2V - 2 - H faces.
  EXPECT_EQ(edges.size(), 3u * 36 - 3 - 20);
  EXPECT_EQ(triangles.size(), 2u * 36 - 2 - 20);
  for (const auto& e : edges) {
    EXPECT_NEAR(e.rel_change, 0.05, 1e-12);
    EXPECT_GE(e.track_a, 100);
    EXPECT_NEAR(e.length_to_mm, 1.05 * e.length_from_mm, 1e-12);
  }
}

TEST(Strain, UniaxialStretchShowsOnlyAlongItsAxis) {
  const auto from = grid_points(5, 0.4);
  auto to = from;
  for (auto& p : to) p.x_mm *= 1.10;
  std::vector<StrainEdge> edges;
  std::vector<StrainTriangle> triangles;
  triangulate_strain(from, to, 3.0, edges, triangles);
  std::map<std::int32_t, TrackedPoint> by_id;
  for (const auto& p : from) by_id[p.track_id] = p;
  for (const auto& e : edges) {
    const auto& a = by_id[e.track_a];
    const auto& b = by_id[e.track_b];
    const double dx = b.x_mm - a.x_mm, dy = b.y_mm - a.y_mm;
    const double expected = std::hypot(1.1 * dx, dy) / std::hypot(dx, dy) - 1;
    EXPECT_NEAR(e.rel_change, expected, 1e-12);
  }
}

TEST(Strain, FarOutlierEdgesAreDroppedWithTheirTriangles) {
  auto from = grid_points(4, 0.5);
  from.push_back({999, 0, FeatureType::pore, 0, 0, 20.0, 0.7});  // joined only by long edges
  std::vector<StrainEdge> edges;
  std::vector<StrainTriangle> triangles;
  triangulate_strain(from, from, 3.0, edges, triangles);
  for (const auto& e : edges) {
    EXPECT_NE(e.track_a, 999);
    EXPECT_NE(e.track_b, 999);
    EXPECT_DOUBLE_EQ(e.rel_change, 0.0);
  }
  for (const auto& t : triangles) {
    for (auto k : t.point_index) EXPECT_NE(k, 16);
  }
  EXPECT_EQ(triangles.size(), 2u * 16 - 2 - 12);
}

// Two-frame tracks on a sheared grid (pixels) whose frame-1 positions are `motion` of their
// frame-0 ones, each carrying the deformation gradients `at0` and `at1` (none if empty).
std::vector<Track> moved_grid(const std::function<Eigen::Vector2d(const Eigen::Vector2d&)>& motion,
                              const std::vector<Eigen::Matrix2d>& gradients) {
  std::vector<Track> tracks;
  for (int j = 0; j < 6; ++j) {
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector2d p0(40 + 20 * i + 1.25 * j, 30 + 20 * j);
      const Eigen::Vector2d p1 = motion(p0);
      Track t;
      t.id = static_cast<std::int32_t>(tracks.size());
      t.x_px = {p0.x(), p1.x()};
      t.y_px = {p0.y(), p1.y()};
      for (const auto& g : gradients) t.gradient.push_back({g(0, 0), g(0, 1), g(1, 0), g(1, 1)});
      tracks.push_back(t);
    }
  }
  return tracks;
}

// The edges of the tracks' one strain frame, in the order of their tracks (a, b).
std::vector<StrainEdge> edges_of(const std::vector<Track>& tracks, double share) {
  const StrainMovie movie =
      strain_from_tracks(tracks, 2, uniform_calibration(50, 320, 240), 60, 1, 3.0, 1, share);
  auto edges = movie.frames.at(0).edges;
  std::sort(edges.begin(), edges.end(), [](const StrainEdge& a, const StrainEdge& b) {
    return std::tie(a.track_a, a.track_b) < std::tie(b.track_a, b.track_b);
  });
  return edges;
}

TEST(Strain, WindowGradientsThatAgreeWithThePositionsChangeNothing) {
  // Skin sheared and turned before frame 0, then stretched by 6 % along x and moved: each
  // window's gradient from frame 0 to 1 is the stretch whatever it was at frame 0.
  Eigen::Matrix2d before;
  before << 1.02, 0.03, -0.05, 0.97;
  const Eigen::Matrix2d stretch = Eigen::Vector2d(1.06, 1.0).asDiagonal();
  const auto tracks = moved_grid(
      [&](const Eigen::Vector2d& p) {
        return Eigen::Vector2d(stretch * p + Eigen::Vector2d(3, -2));
      },
      {before, stretch * before});
  const auto blended = edges_of(tracks, 0.3), plain = edges_of(tracks, 0.0);
  ASSERT_EQ(blended.size(), plain.size());
  ASSERT_GT(blended.size(), 50u);
  for (std::size_t k = 0; k < blended.size(); ++k) {
    EXPECT_NEAR(blended[k].rel_change, plain[k].rel_change, 1e-12);
    EXPECT_GT(plain[k].rel_change, -1e-12);  // a stretch lengthens or keeps every edge
  }
}

TEST(Strain, WindowGradientsAreBlendedInTheirShareAndTheLengthFollows) {
  // Positions stretched by 5 % along x; the windows saw no deformation at all: the blend keeps
  // (1 - share) of the positions' strain.
  const auto stretched = [](const Eigen::Vector2d& p) {
    return Eigen::Vector2d(1.05 * p.x(), p.y());
  };
  const Eigen::Matrix2d none = Eigen::Matrix2d::Identity();
  const auto plain = edges_of(moved_grid(stretched, {none, none}), 0.0);
  const auto blended = edges_of(moved_grid(stretched, {none, none}), 0.3);
  ASSERT_EQ(blended.size(), plain.size());
  for (std::size_t k = 0; k < blended.size(); ++k) {
    EXPECT_NEAR(blended[k].rel_change, 0.7 * plain[k].rel_change, 1e-12);
    EXPECT_NEAR(blended[k].length_to_mm, blended[k].length_from_mm * (1 + blended[k].rel_change),
                1e-12);
  }
  // Tracks that carry no gradients keep the positions' strain at any share.
  const auto without = edges_of(moved_grid(stretched, {}), 0.3);
  ASSERT_EQ(without.size(), plain.size());
  for (std::size_t k = 0; k < without.size(); ++k) {
    EXPECT_EQ(without[k].rel_change, plain[k].rel_change);
  }
}

TEST(Strain, WindowGradientShareOutsideZeroToOneIsRefused) {
  const auto tracks = moved_grid([](const Eigen::Vector2d& p) { return p; }, {});
  for (const double share : {-0.1, 1.5}) {
    try {
      edges_of(tracks, share);
      ADD_FAILURE() << "share " << share << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), ::testing::HasSubstr("window_gradient_share must be 0 to 1"));
    }
  }
}

TEST(Strain, FewerThanThreePointsGiveNoEdges) {
  std::vector<TrackedPoint> two{{1, 0, FeatureType::pore, 0, 0, 0, 0},
                                {2, 0, FeatureType::pore, 0, 0, 1, 0}};
  std::vector<StrainEdge> edges{{}};
  std::vector<StrainTriangle> triangles;
  triangulate_strain(two, two, 3.0, edges, triangles);
  EXPECT_TRUE(edges.empty());
}

// Edges in the same order every time for the same points, whatever the heap looks like (the
// order of CGAL's own edge iterator follows the faces' addresses), on points in general position
// and on points along one line.
TEST(Strain, TheSamePointsGiveTheSameEdgesInTheSameOrder) {
  std::vector<TrackedPoint> scattered;
  std::uint32_t state = 12345;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<double>(state >> 8) / static_cast<double>(1u << 24);
  };
  for (int i = 0; i < 400; ++i) {
    scattered.push_back({i, 0, FeatureType::pore, 0, 0, 10 * next(), 8 * next()});
  }
  std::vector<TrackedPoint> moved = scattered;
  for (auto& p : moved) p.x_mm *= 1.01;
  std::vector<TrackedPoint> line;
  for (int i = 0; i < 40; ++i)
    line.push_back({i, 0, FeatureType::pore, 0, 0, (i * 7 % 40) * 0.1, 0});
  for (const auto* points : {&scattered, &line}) {
    const std::vector<TrackedPoint>& to = points == &scattered ? moved : *points;
    std::vector<StrainEdge> first;
    std::vector<StrainTriangle> triangles;
    triangulate_strain(*points, to, 1e9, first, triangles);
    ASSERT_GT(first.size(), points->size() / 2);
    // A heap with holes of many sizes freed in a scattered order, so that the next
    // triangulation's faces land in another order in memory.
    std::vector<std::vector<char>> clutter;
    for (int round = 0; round < 4; ++round) {
      for (int k = 0; k < 3000; ++k) {
        clutter.emplace_back(16 + static_cast<std::size_t>(next() * 3000), 'x');
      }
      for (auto& block : clutter) {
        if (next() < 0.5) std::vector<char>().swap(block);
      }
      std::vector<StrainEdge> again;
      triangulate_strain(*points, to, 1e9, again, triangles);
      ASSERT_EQ(first.size(), again.size());
      int moved_edges = 0;
      for (std::size_t i = 0; i < first.size(); ++i) {
        moved_edges += first[i].track_a != again[i].track_a || first[i].track_b != again[i].track_b;
      }
      EXPECT_EQ(moved_edges, 0) << "round " << round << " of " << points->size() << " points";
    }
  }
}

// The whole pipeline on a synthetic slide over the bump, compared edge by edge with the exact
// relative length change of the same skin segment (true_rel_change maps both ends through the
// skin model). Measured on this 60-frame sequence (seed 1): see docs/capture-models.md.
class BumpPipeline : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    spec_ = new SceneSpec(testing::short_bump_scene(60));
    sequence_ = new SyntheticSequence(render_sequence(*spec_));
  }
  static void TearDownTestSuite() {
    delete sequence_;
    delete spec_;
  }
  using Errors = EdgeErrors;
  static Errors run(int span) {
    CaptureParams p;
    p.min_track_frames = 20;
    p.span_frames = span;
    p.features.find_minutiae = false;
    const StrainMovie movie =
        measure_strain(sequence_->frames, sequence_->calibration, spec_->frame_rate_hz, p);
    const Errors e = edge_errors(movie, *spec_);
    std::printf("span %d: %ld edges, RMS error %.5f, RMS true strain %.5f, median %zu points\n",
                span, e.edges, e.rms_error, e.rms_truth, e.median_points);
    return e;
  }
  static SceneSpec* spec_;
  static SyntheticSequence* sequence_;
};
SceneSpec* BumpPipeline::spec_ = nullptr;
SyntheticSequence* BumpPipeline::sequence_ = nullptr;

// Consecutive frames: the issue's target is RMS <= 0.005. Between consecutive frames the true
// strain itself is only ~0.0014 RMS, so reporting zero strain would meet that target; the error
// must also be well below the true strain (measured 0.0005, i.e. 0.38 x the truth).
TEST_F(BumpPipeline, ConsecutiveFrameStrainErrorIsBelowHalfAPercent) {
  const Errors e = run(1);
  RecordProperty("rms_error", std::to_string(e.rms_error));
  EXPECT_GT(e.edges, 1000);
  EXPECT_LT(e.rms_error, 0.005);
  EXPECT_LT(e.rms_error, 0.6 * e.rms_truth);
  EXPECT_GE(e.median_points, 100u);
}

// Over 10 frames the true strain (~1.4 % RMS) must stand well above the error: the measurement
// sees the bump, not just noise.
TEST_F(BumpPipeline, TenFrameStrainFollowsTheTruth) {
  const Errors e = run(10);
  EXPECT_GT(e.rms_truth, 0.005);
  EXPECT_LT(e.rms_error, 0.25 * e.rms_truth) << "error " << e.rms_error << " truth " << e.rms_truth;
}

// Each kept track must follow one true landmark: no identity switches along its life.
TEST_F(BumpPipeline, TracksFollowOneTrueLandmarkEach) {
  CaptureParams p;
  p.min_track_frames = 20;
  const StrainMovie movie =
      measure_strain(sequence_->frames, sequence_->calibration, spec_->frame_rate_hz, p);
  std::map<std::pair<int, int>, const TruthLandmark*> truth;  // (frame, id)
  std::map<int, std::vector<const TruthLandmark*>> by_frame;
  for (const auto& lm : sequence_->landmarks) {
    truth[{lm.frame, lm.id}] = &lm;
    by_frame[lm.frame].push_back(&lm);
  }
  std::map<std::int32_t, std::vector<TrackedPoint>> tracks;
  for (const auto& pt : movie.tracks) tracks[pt.track_id].push_back(pt);
  int faithful = 0;
  double se = 0;
  long n = 0;
  for (const auto& [id, pts] : tracks) {
    const TruthLandmark* first = nullptr;
    double best = 1e9;
    for (const auto* lm : by_frame[pts.front().frame]) {
      const double d = std::hypot(lm->x_mm - pts.front().x_mm, lm->y_mm - pts.front().y_mm);
      if (d < best) {
        best = d;
        first = lm;
      }
    }
    bool ok = first != nullptr && best < 0.05;
    for (const auto& pt : pts) {
      const auto it = truth.find({pt.frame, first ? first->id : -1});
      if (it == truth.end()) continue;  // landmark left the contact area (track ran on by gap)
      const double d = std::hypot(it->second->x_mm - pt.x_mm, it->second->y_mm - pt.y_mm);
      ok = ok && d < 0.05;
      se += d * d;
      ++n;
    }
    faithful += ok ? 1 : 0;
  }
  std::printf("%zu tracks, %d follow one landmark within 0.05 mm; RMS %.4f mm\n", tracks.size(),
              faithful, std::sqrt(se / static_cast<double>(n)));
  ASSERT_GT(tracks.size(), 100u);
  EXPECT_GT(faithful, 0.95 * static_cast<double>(tracks.size()));
  // Measured 0.0018 mm (about 0.1 px) after smoothing; 0.005 mm leaves margin, not slack.
  EXPECT_LT(std::sqrt(se / static_cast<double>(n)), 0.005);
}

TEST(Pipeline, RejectsBadInputsClearly) {
  EXPECT_THROW(measure_strain({}, uniform_calibration(60, 10, 10), 60.0), std::invalid_argument);
  std::vector<GrayImage> mixed{{10, 10, std::vector<std::uint8_t>(100)},
                               {11, 10, std::vector<std::uint8_t>(110)}};
  EXPECT_THAT([&] { measure_strain(mixed, uniform_calibration(60, 10, 10), 60.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("frame 1")));
}

TEST(Pipeline, CalibrationForAnotherImageSizeIsRejected) {
  std::vector<GrayImage> frames(3, GrayImage{64, 48, std::vector<std::uint8_t>(64 * 48, 100)});
  EXPECT_THAT([&] { measure_strain(frames, uniform_calibration(60, 640, 484), 60.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(
                  ::testing::HasSubstr("the calibration is for 640 x 484 px images, but the "
                                       "first frame is 64 x 48 px")));
}

// The hole scene through the same pipeline: consecutive-frame error well below the true strain.
TEST(Pipeline, HoleSceneStrainBeatsTheTruthSignal) {
  SceneSpec spec;
  spec.scene = Scene::hole;
  spec.frame_count = 40;
  const auto seq = render_sequence(spec);
  CaptureParams p;
  p.min_track_frames = 20;
  p.span_frames = 5;
  const StrainMovie movie = measure_strain(seq.frames, seq.calibration, spec.frame_rate_hz, p);
  const EdgeErrors e = edge_errors(movie, spec);
  ASSERT_GT(e.edges, 1000);
  std::printf("hole, span 5: RMS error %.5f, RMS true %.5f over %ld edges\n", e.rms_error,
              e.rms_truth, e.edges);
  EXPECT_LT(e.rms_error, 0.4 * e.rms_truth);
}

// The issue's acceptance figures for every scene with strain, on a 60-frame sequence (the bump
// is BumpPipeline above): consecutive-frame edge strain RMS error <= 0.005 against the exact
// truth and a median of >= 100 tracked landmarks per frame; over 10 frames the error must stay
// well below the true strain, so the measurement sees the deformation rather than noise.
class SceneAcceptance : public ::testing::TestWithParam<const char*> {};

TEST_P(SceneAcceptance, ConsecutiveFrameErrorAndYieldMeetTheIssueTargets) {
  SceneSpec spec;
  spec.scene = parse_scene(GetParam());
  spec.frame_count = 60;
  const auto seq = render_sequence(spec);
  for (int span : {1, 10}) {
    CaptureParams p;
    p.min_track_frames = 20;
    p.span_frames = span;
    const StrainMovie movie = measure_strain(seq.frames, seq.calibration, spec.frame_rate_hz, p);
    const EdgeErrors e = edge_errors(movie, spec);
    ASSERT_GT(e.edges, 1000);
    std::printf("%s, span %d: RMS error %.5f, RMS true %.5f, median %zu points\n", GetParam(), span,
                e.rms_error, e.rms_truth, e.median_points);
    if (span == 1) {
      EXPECT_LT(e.rms_error, 0.005);
      EXPECT_GE(e.median_points, 100u);
    } else {
      EXPECT_GT(e.rms_truth, 0.003);
      EXPECT_LT(e.rms_error, 0.3 * e.rms_truth);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SceneAcceptance,
                         ::testing::Values("hole", "flat-rotate", "flat-stick-slip"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(Pipeline, NoContactGivesAnEmptyButWellFormedMovie) {
  std::vector<GrayImage> blank(40, GrayImage{64, 48, std::vector<std::uint8_t>(64 * 48, 230)});
  const StrainMovie m = measure_strain(blank, uniform_calibration(60, 64, 48), 60.0);
  EXPECT_TRUE(m.tracks.empty());
  ASSERT_EQ(m.frames.size(), 39u);
  for (const auto& f : m.frames) EXPECT_TRUE(f.edges.empty());
}

}  // namespace
}  // namespace tactile::capture
