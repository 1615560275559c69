#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "tactile/capture/baselines.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/evaluate.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/capture/synth.hpp"
#include "tactile/common/error.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

using testing::TempDir;

// Tracks made of the true landmark positions: what a perfect tracker would report.
std::vector<Track> true_tracks(const SyntheticSequence& seq) {
  std::map<std::int32_t, std::map<std::int32_t, const TruthLandmark*>> by_id;
  for (const auto& lm : seq.landmarks) by_id[lm.id][lm.frame] = &lm;
  std::vector<Track> tracks;
  for (const auto& [id, frames] : by_id) {
    // Only the first unbroken run of frames: a Track has no holes.
    Track t;
    t.id = static_cast<std::int32_t>(tracks.size());
    t.type = frames.begin()->second->type;
    t.first_frame = frames.begin()->first;
    for (auto it = frames.begin(); it != frames.end(); ++it) {
      if (it->first != t.first_frame + static_cast<int>(t.x_px.size())) break;
      t.x_px.push_back(it->second->x_px);
      t.y_px.push_back(it->second->y_px);
    }
    if (t.x_px.size() >= 2) tracks.push_back(std::move(t));
  }
  return tracks;
}

class Evaluate : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    SceneSpec spec = testing::short_bump_scene(12);
    sequence_ = new SyntheticSequence(render_sequence(spec));
  }
  static void TearDownTestSuite() {
    delete sequence_;
    sequence_ = nullptr;
  }
  static GroundTruth truth() {
    return {sequence_->spec, sequence_->calibration, sequence_->landmarks, {}};
  }
  static StrainMovie perfect_movie(int span) {
    return strain_from_tracks(true_tracks(*sequence_), sequence_->spec.frame_count,
                              sequence_->calibration, sequence_->spec.frame_rate_hz, span, 3.0);
  }
  static SyntheticSequence* sequence_;
};
SyntheticSequence* Evaluate::sequence_ = nullptr;

TEST_F(Evaluate, TrueTrajectoriesHaveNoStrainOrLocalisationError) {
  const Evaluation ev = evaluate_strain(perfect_movie(3), truth());
  ASSERT_GT(ev.edges, 100);
  EXPECT_GT(ev.rms_truth, 1e-4);  // the bump does strain the skin
  EXPECT_LT(ev.rms_error, 1e-6);  // only the forward map's iteration tolerance remains
  EXPECT_LT(ev.localisation_rms_mm, 1e-9);
  EXPECT_EQ(ev.unmatched_points, 0);
  EXPECT_GT(ev.median_yield, 0.9);  // every landmark in contact is tracked
  EXPECT_LE(ev.median_yield, 1.0);
}

// A measurement that sees every frame_to position scaled by 1 + s about the image origin reports
// (1 + s)(1 + e) - 1 for a true change e: an error of s (1 + e), so an RMS error close to s.
TEST_F(Evaluate, AKnownScaleErrorShowsAsThatRmsError) {
  StrainMovie movie = perfect_movie(1);
  constexpr double s = 0.01;
  for (auto& f : movie.frames) {
    for (auto& e : f.edges) e.rel_change = (1 + s) * (1 + e.rel_change) - 1;
  }
  const Evaluation ev = evaluate_strain(movie, truth());
  EXPECT_NEAR(ev.rms_error, s, 0.0005);
  for (const auto& f : ev.frames) {
    if (f.edges > 0) {
      EXPECT_NEAR(f.rms_error, s, 0.0005) << "frame " << f.frame_from;
    }
  }
}

TEST_F(Evaluate, TrackLengthsAreCounted) {
  StrainMovie movie;
  movie.tracks = {{0, 0, FeatureType::pore, 0, 0, 0, 0},
                  {0, 1, FeatureType::pore, 0, 0, 0, 0},
                  {0, 2, FeatureType::pore, 0, 0, 0, 0},
                  {1, 0, FeatureType::pore, 0, 0, 0, 0}};
  const Evaluation ev = evaluate_strain(movie, truth());
  EXPECT_EQ(ev.track_count, 2);
  EXPECT_DOUBLE_EQ(ev.mean_track_frames, 2.0);
}

TEST_F(Evaluate, EmptyMovieGivesZeroCountsNotAnError) {
  const Evaluation ev = evaluate_strain(StrainMovie{}, truth());
  EXPECT_EQ(ev.edges, 0);
  EXPECT_EQ(ev.rms_error, 0.0);
  EXPECT_EQ(ev.track_count, 0);
  EXPECT_TRUE(ev.frames.empty());
}

TEST_F(Evaluate, GroundTruthRoundTripsThroughTheSynthFolder) {
  TempDir dir;
  write_sequence(dir.path(), *sequence_);
  const GroundTruth gt = read_ground_truth(dir.path());
  EXPECT_EQ(gt.spec.scene, sequence_->spec.scene);
  EXPECT_EQ(gt.spec.frame_count, sequence_->spec.frame_count);
  EXPECT_DOUBLE_EQ(gt.spec.speed_mm_per_s, sequence_->spec.speed_mm_per_s);
  ASSERT_EQ(gt.landmarks.size(), sequence_->landmarks.size());
  EXPECT_NEAR(gt.landmarks.back().x_px, sequence_->landmarks.back().x_px, 1e-4);
  write_evaluation_csv(dir.path() / "eval", evaluate_strain(perfect_movie(1), gt));
  std::ifstream in(dir.path() / "eval" / "evaluation_frames.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "frame_from,frame_to,edges,rms_error,rms_truth,tracked_points,truth_landmarks");
}

// Writes `text` to dir/name.
void put(const std::filesystem::path& dir, const char* name, const std::string& text) {
  std::ofstream(dir / name) << text;
}

void expect_format_error(const std::filesystem::path& dir, const std::string& fragment) {
  try {
    read_ground_truth(dir);
    ADD_FAILURE() << "no error; expected one mentioning " << fragment;
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST_F(Evaluate, BadGroundTruthFoldersAreNamedErrors) {
  TempDir dir;
  expect_format_error(dir.path(), "scene.json");  // not a synth folder at all
  put(dir.path(), "scene.json", "{ not json");
  expect_format_error(dir.path(), "not valid JSON");
  put(dir.path(), "scene.json", R"({"format": "tactile-calibration"})");
  expect_format_error(dir.path(), "tactile-synthetic-scene");
  put(dir.path(), "scene.json", R"({"format": "tactile-synthetic-scene", "spec": {"scene": 3}})");
  expect_format_error(dir.path(), "'scene' has the wrong type");
  put(dir.path(), "scene.json",
      R"({"format": "tactile-synthetic-scene", "spec": {"scene": "cube"}})");
  expect_format_error(dir.path(),
                      "spec: unknown scene 'cube' (known: bump, hole, flat-slide, flat-rotate, "
                      "flat-stick-slip)");

  write_sequence(dir.path(), *sequence_);  // a good folder, then break its landmarks
  put(dir.path(), "landmarks.csv", "");
  expect_format_error(dir.path(), "expected header");
  put(dir.path(), "landmarks.csv",
      "id,type,frame,x_px,y_px,x_mm,y_mm,diameter_mm\n1,pore,0,1,2,3\n");
  expect_format_error(dir.path(), "line 2");
  put(dir.path(), "landmarks.csv",
      "id,type,frame,x_px,y_px,x_mm,y_mm,diameter_mm\n1,wart,0,1,2,3,4,5\n");
  expect_format_error(dir.path(), "unknown type 'wart'");
  put(dir.path(), "landmarks.csv",
      "id,type,frame,x_px,y_px,x_mm,y_mm,diameter_mm\n1,pore,999,1,2,3,4,5\n");
  expect_format_error(dir.path(), "frame 999");
  // A wrong header is named as it is, beside the one expected.
  put(dir.path(), "landmarks.csv", "id;type;frame\n1;pore;0\n");
  expect_format_error(dir.path(), "line 1: header is 'id;type;frame', expected header id,type,");
}

// Saved by a spreadsheet on Windows: CR LF line ends and a UTF-8 byte-order mark.
TEST_F(Evaluate, LandmarksWithCrLfAndAByteOrderMarkAreRead) {
  TempDir dir;
  write_sequence(dir.path(), *sequence_);
  std::string text;
  {
    std::ifstream in(dir.path() / "landmarks.csv");
    for (std::string line; std::getline(in, line);) text += line + "\r\n";
  }
  put(dir.path(), "landmarks.csv", "\xEF\xBB\xBF" + text);
  const GroundTruth gt = read_ground_truth(dir.path());
  ASSERT_EQ(gt.landmarks.size(), sequence_->landmarks.size());
  EXPECT_NEAR(gt.landmarks.back().x_px, sequence_->landmarks.back().x_px, 1e-4);
}

// A rigid slide: every skin point moves speed / rate mm per frame along +x, so the baselines'
// tracks must move by that many pixels per frame, and their strain must be near zero.
TEST(Baselines, TrackARigidSlideAtTheTrueSpeed) {
  SceneSpec spec;
  spec.scene = Scene::flat_slide;
  spec.frame_count = 36;
  const SyntheticSequence seq = render_sequence(spec);
  const double px_per_frame =
      spec.speed_mm_per_s / spec.frame_rate_hz / (spec.field_width_mm / spec.width_px);
  for (const auto& [name, tracks] :
       {std::pair{"LK", track_lucas_kanade(seq.frames, seq.calibration)},
        std::pair{"DIS", track_dis_flow(seq.frames, seq.calibration)}}) {
    ASSERT_GT(tracks.size(), 50u) << name;
    std::vector<double> rates;
    for (const auto& t : tracks) {
      EXPECT_GE(t.x_px.size(), 30u) << name;  // min_track_frames
      rates.push_back((t.x_px.back() - t.x_px.front()) / (t.x_px.size() - 1.0));
    }
    std::nth_element(rates.begin(), rates.begin() + rates.size() / 2, rates.end());
    EXPECT_NEAR(rates[rates.size() / 2], px_per_frame, 0.05) << name;
  }
}

TEST(Baselines, MixedSizesAreRejectedAndNoFramesGiveNoTracks) {
  GrayImage a{32, 32, std::vector<std::uint8_t>(32 * 32, 100)};
  GrayImage b{16, 32, std::vector<std::uint8_t>(16 * 32, 100)};
  const Calibration c = uniform_calibration(50, 32, 32);
  EXPECT_THROW(track_lucas_kanade({a, b}, c), std::invalid_argument);
  EXPECT_THROW(track_dis_flow({a, b}, c), std::invalid_argument);
  EXPECT_TRUE(track_lucas_kanade({}, c).empty());
  EXPECT_TRUE(track_dis_flow({}, c).empty());
  // Featureless frames (no print in contact): nothing to track, not an error.
  EXPECT_TRUE(track_lucas_kanade(std::vector<GrayImage>(40, a), c).empty());
  EXPECT_TRUE(track_dis_flow(std::vector<GrayImage>(40, a), c).empty());
}

// No skin touches the glass: the whole pipeline gives strain frames without edges.
TEST(Pipeline, SequenceWithNoContactGivesEmptyStrainFrames) {
  GrayImage bright{640, 484, std::vector<std::uint8_t>(640 * 484, 230)};
  const auto movie =
      measure_strain(std::vector<GrayImage>(40, bright), uniform_calibration(62, 640, 484), 60.0);
  EXPECT_TRUE(movie.tracks.empty());
  ASSERT_EQ(movie.frames.size(), 39u);
  for (const auto& f : movie.frames) EXPECT_TRUE(f.edges.empty());
}

}  // namespace
}  // namespace tactile::capture
