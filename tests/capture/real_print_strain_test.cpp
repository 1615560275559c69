// Strain on real skin: real PolyU HRF prints moved by an exact warp (print_warp.hpp), measured
// with the default settings and against Lucas-Kanade on the same sequences.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <tuple>

#include "../common/temp_dir.hpp"
#include "real_prints.hpp"
#include "tactile/capture/baselines.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/evaluate.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/capture/print_warp.hpp"
#include "tactile/common/error.hpp"

namespace tactile::capture {
namespace {

namespace fs = std::filesystem;

using test::marks_of;
using test::print_path;
using test::spec_for;

// A movie's tracked points back as tracks (each track's points are consecutive frames).
std::vector<Track> tracks_of(const StrainMovie& movie) {
  std::map<std::int32_t, Track> by_id;
  for (const auto& p : movie.tracks) {
    Track& t = by_id[p.track_id];
    if (t.x_px.empty()) {
      t.id = p.track_id;
      t.first_frame = p.frame;
    }
    t.x_px.push_back(p.x_px);
    t.y_px.push_back(p.y_px);
  }
  std::vector<Track> tracks;
  for (auto& [id, t] : by_id) tracks.push_back(std::move(t));
  return tracks;
}

TEST(PrintWarp, ImageAndMaterialMapsInvertEachOther) {
  for (const auto& [pattern, name] : kWarpPatternNames) {
    PrintWarpSpec s;
    s.width_px = 320;
    s.height_px = 240;
    s.pattern = parse_warp_pattern(name);
    EXPECT_EQ(s.pattern, pattern) << name;
    s.strain = 0.08;
    for (int frame : {0, 7, 14, 29}) {
      for (const PointMm m : {PointMm{0.3, 0.4}, PointMm{3.4, 2.5}, PointMm{6.0, 4.9}}) {
        const PointMm back = warp_to_material(s, warp_to_image(s, m, frame), frame);
        EXPECT_NEAR(back.x_mm, m.x_mm, 1e-9) << name << " frame " << frame;
        EXPECT_NEAR(back.y_mm, m.y_mm, 1e-9) << name << " frame " << frame;
      }
    }
  }
}

TEST(PrintWarp, StrainOfAShortSegmentIsThePatternsStrain) {
  PrintWarpSpec s;
  s.width_px = 321;  // centre on a pixel: (320 / 2) / 47 mm
  s.height_px = 241;
  s.rotation_deg = 0;
  s.frame_count = 31;  // frame 15 is the peak: sin(pi / 2) = 1
  const PointMm c{160 / s.px_per_mm, 120 / s.px_per_mm};
  const double h = 1e-4;
  auto segment_strain = [&](WarpPattern p, PointMm dir) {
    s.pattern = p;
    s.strain = 0.05;
    const PointMm a{c.x_mm - h * dir.x_mm, c.y_mm - h * dir.y_mm};
    const PointMm b{c.x_mm + h * dir.x_mm, c.y_mm + h * dir.y_mm};
    return warp_rel_change(s, a, b, 0, 15);  // frame 0 is undeformed (and not slid yet)
  };
  // At the centre of the Gaussian patterns the displacement is strain x offset.
  EXPECT_NEAR(segment_strain(WarpPattern::stretch, {1, 0}), 0.05, 1e-6);
  EXPECT_NEAR(segment_strain(WarpPattern::stretch, {0, 1}), 0.0, 1e-6);
  EXPECT_NEAR(segment_strain(WarpPattern::compress, {0, 1}), -0.05, 1e-6);
  EXPECT_NEAR(segment_strain(WarpPattern::bump, {0.6, 0.8}), 0.05, 1e-6);
  EXPECT_NEAR(segment_strain(WarpPattern::rigid, {1, 0}), 0.0, 1e-12);
  // The wave at mid-sequence has travelled half a wavelength: strain a cos(k x - pi) = -a at
  // the centre.
  EXPECT_NEAR(segment_strain(WarpPattern::wave, {1, 0}), -0.05, 1e-6);
}

TEST(PrintWarp, FirstFrameWithoutCameraEffectsIsThePrint) {
  const GrayImage print = read_image(print_path("12", "image_"));
  PrintWarpSpec s = spec_for(print, WarpPattern::wave, 0.04);
  s.noise_sigma = 0;
  s.blur_sigma_px = 0;
  s.brightness_drift = 0;
  const PrintSequence seq = render_print_sequence(s, print);
  ASSERT_EQ(seq.frames.size(), 30u);
  EXPECT_EQ(seq.frames[0].pixels, print.pixels);
  EXPECT_NE(seq.frames[29].pixels, print.pixels);  // slid and rotated by the last frame
}

TEST(PrintWarp, TravellingPatternsCrossAtTheirSpeed) {
  PrintWarpSpec s;
  s.width_px = 321;
  s.height_px = 241;
  s.rotation_deg = 0;
  s.slide_x_mm = 0;
  s.slide_y_mm = 0;
  s.frame_count = 31;  // 0.5 s at 60 Hz: the pattern is at the centre at frame 15
  s.frame_rate_hz = 60;
  s.travel_speed_mm_per_s = 10;
  s.strain = 0.05;
  const PointMm c{160 / s.px_per_mm, 120 / s.px_per_mm};
  // Strain along x of a short segment at the centre plus `ahead` mm, frame 0 to `frame`.
  auto strain_at = [&](WarpPattern p, double ahead, int frame) {
    s.pattern = p;
    const double h = 1e-4;
    return warp_rel_change(s, {c.x_mm + ahead - h, c.y_mm}, {c.x_mm + ahead + h, c.y_mm}, 0, frame);
  };
  // The segment 1 mm ahead of the centre starts 3.5 mm ahead of either pattern (sigma = 3 mm /
  // 2.355 = 1.274 mm; g = exp(-3.5^2 / (2 sigma^2)) = 0.0230), where the ridge's strain is -a g
  // and the pulse's a g (1 - 3.5^2 / sigma^2). Six frames (0.1 s) after mid-sequence the pattern
  // has moved 1 mm on and sits on the segment: strain -a (ridge) and a (pulse); at mid-sequence
  // it is 1 mm behind: ridge -a exp(-1 / (2 sigma^2)) = -0.735 a.
  const double sigma = 3.0 / 2.3548, g = std::exp(-3.5 * 3.5 / (2 * sigma * sigma));
  const double a = 0.05;
  EXPECT_NEAR(strain_at(WarpPattern::ridge, 1.0, 21), (1 - a) / (1 - a * g) - 1, 0.001);
  EXPECT_NEAR(strain_at(WarpPattern::pulse, 1.0, 21),
              (1 + a) / (1 + a * g * (1 - 3.5 * 3.5 / (sigma * sigma))) - 1, 0.001);
  EXPECT_NEAR(strain_at(WarpPattern::ridge, 1.0, 15),
              (1 - a * std::exp(-1 / (2 * sigma * sigma))) / (1 - a * g) - 1, 0.001);
  // The stick-slip centre never moves; its rim does.
  s.travel_speed_mm_per_s = 20;
  for (int f : {3, 9, 17, 30}) EXPECT_NEAR(strain_at(WarpPattern::stick_slip, 0.0, f), 0, 1e-12);
  double largest = 0;
  for (int f = 1; f < 31; ++f) {
    largest = std::max(largest, std::abs(strain_at(WarpPattern::stick_slip, 2.6, f)));
  }
  EXPECT_GT(largest, 0.02);
  EXPECT_LT(largest, 0.06);
}

TEST(PrintWarp, ContactLossHidesPoresAndBrightensTheirSkin) {
  const GrayImage print = read_image(print_path("12", "image_"));
  const auto marks = marks_of("12", print);
  PrintWarpSpec s = spec_for(print, WarpPattern::rigid, 0.0);
  s.frame_count = 9;
  s.contact_loss = 1;
  s.noise_sigma = 0;
  const PrintSequence seq = render_print_sequence(s, print, marks);
  s.contact_loss = 0;
  const PrintSequence touching = render_print_sequence(s, print, marks);
  auto count = [](const PrintSequence& q, int frame) {
    return std::count_if(q.landmarks.begin(), q.landmarks.end(),
                         [&](const TruthLandmark& lm) { return lm.frame == frame; });
  };
  // In the middle the lifted region hides some marks; at both ends it is down.
  EXPECT_LT(count(seq, 4), count(touching, 4) - 10);
  EXPECT_EQ(count(seq, 0), count(touching, 0));
  EXPECT_EQ(count(seq, 8), count(touching, 8));
  // The lifted region's centre (0.2 of the field right of and 0.15 above the middle) is bright
  // and featureless at mid-sequence.
  const int x = static_cast<int>(print.width_px * 0.7),
            y = static_cast<int>(print.height_px * 0.35);
  double mean = 0, sq = 0;
  int n = 0;
  for (int v = y - 4; v <= y + 4; ++v) {
    for (int u = x - 4; u <= x + 4; ++u) {
      const double g = seq.frames[4].pixels[static_cast<std::size_t>(v * print.width_px + u)];
      mean += g;
      sq += g * g;
      ++n;
    }
  }
  mean /= n;
  EXPECT_LT(std::sqrt(sq / n - mean * mean), 3.0);
}

TEST(PrintWarp, ExposureBlursAlongTheMotion) {
  const GrayImage print = read_image(print_path("12", "image_"));
  PrintWarpSpec s = spec_for(print, WarpPattern::rigid, 0.0);
  s.frame_count = 3;
  s.noise_sigma = 0;
  s.blur_sigma_px = 0;
  s.brightness_drift = 0;
  s.rotation_deg = 0;
  s.slide_y_mm = 0;
  s.slide_x_mm = 0.4;  // 0.2 mm = 9.4 px a frame
  s.supersample = 4;
  // Grey-level differences along x (the motion) and along y.
  auto contrast = [&](const GrayImage& g, int dx, int dy) {
    double sum = 0;
    for (int y = 20; y < g.height_px - 20; ++y) {
      for (int x = 20; x < g.width_px - 20; ++x) {
        const auto at = [&](int u, int v) {
          return static_cast<double>(g.pixels[static_cast<std::size_t>(v * g.width_px + u)]);
        };
        sum += std::abs(at(x + dx, y + dy) - at(x, y));
      }
    }
    return sum;
  };
  const GrayImage still = render_print_sequence(s, print).frames[1];
  s.exposure_s = 1 / s.frame_rate_hz;
  const GrayImage moving = render_print_sequence(s, print).frames[1];
  // A 9 px smear flattens the x differences far more than the y ones.
  const double x_ratio = contrast(moving, 1, 0) / contrast(still, 1, 0);
  const double y_ratio = contrast(moving, 0, 1) / contrast(still, 0, 1);
  EXPECT_LT(x_ratio, 0.6);
  EXPECT_LT(x_ratio, 0.8 * y_ratio);
}

TEST(PrintWarp, MarksFollowTheWarp) {
  const GrayImage print = read_image(print_path("12", "image_"));
  const auto marks = marks_of("12", print);
  const PrintWarpSpec s = spec_for(print, WarpPattern::bump, 0.06);
  const PrintSequence seq = render_print_sequence(s, print, marks);
  int at_frame_0 = 0;
  for (const auto& lm : seq.landmarks) {
    const auto& m = marks[static_cast<std::size_t>(lm.id)];
    const PointMm x = warp_to_image(s, {m[0] / s.px_per_mm, m[1] / s.px_per_mm}, lm.frame);
    EXPECT_NEAR(lm.x_mm, x.x_mm, 1e-9);
    EXPECT_NEAR(lm.x_px, x.x_mm * s.px_per_mm, 1e-6);
    if (lm.frame == 0) ++at_frame_0;
  }
  EXPECT_EQ(at_frame_0, static_cast<int>(marks.size()));  // every mark is in view at first
}

TEST(PrintWarp, BadSpecsAreRefusedWithReadableNumbers) {
  const GrayImage print = read_image(print_path("12", "image_"));
  PrintWarpSpec s = spec_for(print, WarpPattern::wave, 0.5);
  try {
    render_print_sequence(s, print);
    FAIL() << "strain 0.5 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("strain 0.5 is out of range"), std::string::npos)
        << e.what();
  }
  s.strain = 0.04;
  s.width_px = 100;
  EXPECT_THROW(render_print_sequence(s, print), std::invalid_argument);
  EXPECT_THROW(parse_warp_pattern("zigzag"), std::invalid_argument);
}

TEST(PrintWarp, SequenceFolderIsAGroundTruthAndBrokenOnesAreNamed) {
  const tactile::test::TempDir dir;
  const GrayImage print = read_image(print_path("12", "image_"));
  PrintWarpSpec s = spec_for(print, WarpPattern::stretch, 0.03);
  s.frame_count = 3;
  const auto marks = marks_of("12", print);
  write_print_sequence(dir.path(), render_print_sequence(s, print, marks));
  const GroundTruth truth = read_ground_truth(dir.path());
  ASSERT_TRUE(truth.warp.has_value());
  EXPECT_EQ(truth.warp->pattern, WarpPattern::stretch);
  EXPECT_EQ(truth_frame_count(truth), 3);
  EXPECT_DOUBLE_EQ(truth.warp->strain, 0.03);
  EXPECT_GT(truth.landmarks.size(), 2 * marks.size());

  // A pattern no reader knows, and a strain no renderer accepts: named, not crashed.
  const fs::path scene = dir.path() / "scene.json";
  std::ifstream in(scene);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& [from, to, expect] :
       {std::tuple<std::string, std::string, std::string>{"\"stretch\"", "\"zigzag\"", "zigzag"},
        {"\"strain\": 0.03", "\"strain\": 3", "strain 3 is out of range"},
        {"\"frame_count\": 3", "\"frame_count\": \"three\"", "frame_count"}}) {
    std::string broken = text;
    const auto at = broken.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    broken.replace(at, from.size(), to);
    std::ofstream(scene) << broken;
    try {
      read_ground_truth(dir.path());
      ADD_FAILURE() << "accepted " << to;
    } catch (const FormatError& e) {
      EXPECT_NE(std::string(e.what()).find("scene.json"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  }
}

// The landmarks the choice found on the first frame are the ones the capture would detect
// there, and handing them over changes nothing in the strain.
TEST(RealPrintStrain, TheChoicesFirstFrameLandmarksAreTheCapturesOwn) {
  const GrayImage print = read_image(print_path("12", "image_"));
  PrintWarpSpec spec = spec_for(print, WarpPattern::wave, 0.04);
  spec.frame_count = 12;
  const PrintSequence seq = render_print_sequence(spec, print);
  const CaptureChoice choice = choose_capture_settings(seq.frames[0], spec.px_per_mm);
  ASSERT_EQ(choice.detector, PoreDetector::ridge_blob);
  FeatureParams ridge_blob = pores_only();
  ridge_blob.pore_detector = PoreDetector::ridge_blob;
  const auto detected = extract_features(seq.frames[0], spec.px_per_mm, ridge_blob);
  ASSERT_EQ(choice.first_frame_features.size(), detected.size());
  EXPECT_EQ(static_cast<int>(detected.size()), choice.ridge_blob_pores);
  for (std::size_t i = 0; i < detected.size(); ++i) {
    EXPECT_EQ(choice.first_frame_features[i].x_px, detected[i].x_px);
    EXPECT_EQ(choice.first_frame_features[i].y_px, detected[i].y_px);
  }
  CaptureParams handed = with_choice({}, choice);
  handed.refinement.min_frames = 5;
  CaptureParams detecting = handed;
  detecting.first_frame_features.clear();
  const StrainMovie a = measure_strain(seq.frames, seq.calibration, 60, handed);
  const StrainMovie b = measure_strain(seq.frames, seq.calibration, 60, detecting);
  ASSERT_EQ(a.tracks.size(), b.tracks.size());
  ASSERT_GT(a.tracks.size(), 100u);
  for (std::size_t i = 0; i < a.tracks.size(); ++i) {
    EXPECT_EQ(a.tracks[i].x_px, b.tracks[i].x_px);
    EXPECT_EQ(a.tracks[i].y_px, b.tracks[i].y_px);
  }
}

// The acceptance figures on two prints that no setting of the strain pipeline was tuned on
// (the refinement was tuned on prints 01-10; the shipped pore model was trained on all 15).
// Asserted on the 8 % travelling wave and the 4 % bump: >= 150 tracked landmarks per frame, edge
// strain RMS error <= 0.0025, correlation with the exact warp >= 0.96, and better than
// Lucas-Kanade on the same frames in both error and correlation. The figures over 5 frames are
// printed. The still patterns are asserted below; the 1 % wave, whose strain changes over the
// sequence's own length, reaches 0.94-0.96 (docs/capture-models.md) and is not asserted.
TEST(RealPrintStrain, HeldOutPrintsMeetTheTargetsAndBeatLucasKanade) {
  for (const auto& [nn, pattern, strain] :
       {std::tuple{"12", WarpPattern::wave, 0.08}, std::tuple{"14", WarpPattern::wave, 0.08},
        std::tuple{"12", WarpPattern::bump, 0.04}, std::tuple{"14", WarpPattern::bump, 0.04}}) {
    SCOPED_TRACE(fmt::format("print {}, {} at {} %", nn, to_string(pattern), 100 * strain));
    const GrayImage print = read_image(print_path(nn, "image_"));
    const auto marks = marks_of(nn, print);
    const PrintSequence seq = render_print_sequence(spec_for(print, pattern, strain), print, marks);
    const GroundTruth truth = ground_truth_of(seq);

    const CaptureChoice choice = choose_capture_settings(seq.frames[0], seq.spec.px_per_mm);
    EXPECT_EQ(choice.detector, PoreDetector::ridge_blob) << nn;
    const CaptureParams params = with_choice({}, choice);
    const StrainMovie movie = measure_strain(seq.frames, seq.calibration, 60, params);
    const Evaluation ours = evaluate_strain(movie, truth);
    const Evaluation ours_span5 =
        evaluate_strain(strain_from_tracks(tracks_of(movie), movie.camera_frame_count,
                                           seq.calibration, 60, 5, params.max_edge_ratio),
                        truth);
    const Evaluation lk =
        evaluate_strain(strain_from_tracks(track_lucas_kanade(seq.frames, seq.calibration),
                                           static_cast<int>(seq.frames.size()), seq.calibration, 60,
                                           1, params.max_edge_ratio),
                        truth);
    std::printf(
        "print %s, %s: ours tracked %.0f rms %.5f corr %.4f; Lucas-Kanade tracked %.0f rms %.5f "
        "corr %.4f (true strain rms %.5f)\n",
        nn, std::string(to_string(pattern)).c_str(), ours.median_tracked_points, ours.rms_error,
        ours.correlation, lk.median_tracked_points, lk.rms_error, lk.correlation, ours.rms_truth);
    std::printf("print %s over 5 frames: ours rms %.5f corr %.4f (true strain rms %.5f)\n", nn,
                ours_span5.rms_error, ours_span5.correlation, ours_span5.rms_truth);
    EXPECT_GE(ours.median_tracked_points, 150) << nn;
    EXPECT_LE(ours.rms_error, 0.0025) << nn;
    EXPECT_GE(ours.correlation, 0.96) << nn;
    EXPECT_LT(ours.rms_error, lk.rms_error) << nn;
    EXPECT_GT(ours.correlation, lk.correlation) << nn;
  }
}

// The sequence captured at 60 Hz with `params`, scored against its exact warp.
Evaluation strain_scored(const PrintSequence& seq, const CaptureParams& params) {
  return evaluate_strain(measure_strain(seq.frames, seq.calibration, 60, params),
                         ground_truth_of(seq));
}

// A capture scored with `params` (ours) and with one of its settings changed (other), both
// printed under `label` with `other_name` for the second.
struct ScoredAgainst {
  Evaluation ours, other;
};
ScoredAgainst scored_against(const PrintSequence& seq, const CaptureParams& params,
                             const std::function<void(CaptureParams&)>& change,
                             const std::string& label, const std::string& other_name) {
  CaptureParams changed = params;
  change(changed);
  const ScoredAgainst s{strain_scored(seq, params), strain_scored(seq, changed)};
  std::printf(
      "%s: tracked %.0f rms %.5f corr %.4f; %s: tracked %.0f rms %.5f corr %.4f (true "
      "strain rms %.5f)\n",
      label.c_str(), s.ours.median_tracked_points, s.ours.rms_error, s.ours.correlation,
      other_name.c_str(), s.other.median_tracked_points, s.other.rms_error, s.other.correlation,
      s.ours.rms_truth);
  return s;
}

// The quasi-static figures on the same two held-out prints: a stretch and a compression of 4 %
// rising and falling over 30 frames, where the true frame-to-frame strain is only about 0.0007
// RMS, so the trackers' noise is most of what is measured: edge strain RMS error <= 0.0003 and
// correlation with the exact warp >= 0.97.
TEST(RealPrintStrain, HeldOutPrintsKeepTheQuasiStaticFigures) {
  for (const auto& [nn, pattern] :
       {std::pair{"12", WarpPattern::stretch}, std::pair{"14", WarpPattern::stretch},
        std::pair{"12", WarpPattern::compress}, std::pair{"14", WarpPattern::compress}}) {
    SCOPED_TRACE(fmt::format("print {}, {}", nn, to_string(pattern)));
    const GrayImage print = read_image(print_path(nn, "image_"));
    const auto marks = marks_of(nn, print);
    const PrintSequence seq = render_print_sequence(spec_for(print, pattern, 0.04), print, marks);
    const CaptureParams params =
        with_choice({}, choose_capture_settings(seq.frames[0], seq.spec.px_per_mm));
    const Evaluation ours = strain_scored(seq, params);
    std::printf("print %s, %s: tracked %.0f rms %.5f corr %.4f (true strain rms %.5f)\n", nn,
                std::string(to_string(pattern)).c_str(), ours.median_tracked_points, ours.rms_error,
                ours.correlation, ours.rms_truth);
    EXPECT_LT(ours.rms_truth, 0.0015);  // or this is not the quasi-static sequence
    EXPECT_GE(ours.median_tracked_points, 150);
    EXPECT_LE(ours.rms_error, 0.0003);
    EXPECT_GE(ours.correlation, 0.97);
  }
}

// The weakest quasi-static sequence: a wave of 1 % strain, whose true frame-to-frame strain is
// so small that the trackers' noise is a quarter of it. Each alignment window measures the
// skin's deformation across it as well as its landmark's position, and the two carry partly
// different noise: with their share blended in, each edge's strain follows the exact warp more
// closely than from the positions alone, on held-out prints (the share was chosen on others).
TEST(RealPrintStrain, HeldOutPrintsSlowWaveFollowsTheTruthBetterWithTheWindowsDeformation) {
  for (const char* nn : {"12", "14"}) {
    SCOPED_TRACE(fmt::format("print {}", nn));
    const GrayImage print = read_image(print_path(nn, "image_"));
    const auto marks = marks_of(nn, print);
    const PrintSequence seq =
        render_print_sequence(spec_for(print, WarpPattern::wave, 0.01), print, marks);
    const CaptureParams params =
        with_choice({}, choose_capture_settings(seq.frames[0], seq.spec.px_per_mm));
    ASSERT_GT(params.window_gradient_share, 0);
    const auto [ours, positions] = scored_against(
        seq, params, [](CaptureParams& p) { p.window_gradient_share = 0; },
        fmt::format("print {}, 1 % wave", nn), "positions alone");
    EXPECT_LT(ours.rms_truth, 0.001);  // or this is not the slow wave
    EXPECT_GT(ours.correlation, positions.correlation + 0.002);
    EXPECT_LT(ours.rms_error, positions.rms_error);
    EXPECT_EQ(ours.median_tracked_points, positions.median_tracked_points);
  }
}

// The fast scene on print nn: a strain wave of 8 % crossing at travel_mm_per_s, filmed at 60 Hz
// with a 2 ms exposure by a camera that integrates each pixel's area, while the finger slides
// at 2.5 mm/s and turns by 3 degrees.
PrintSequence fast_scene(const std::string& nn, double travel_mm_per_s, int frame_count) {
  const GrayImage print = read_image(print_path(nn, "image_"));
  const auto marks = marks_of(nn, print);
  PrintWarpSpec spec = spec_for(print, WarpPattern::wave, 0.08);
  spec.frame_count = frame_count;
  spec.frame_rate_hz = 60;
  spec.travel_speed_mm_per_s = travel_mm_per_s;
  spec.slide_x_mm = 2.5 * sequence_duration_s(spec);
  spec.slide_y_mm = 0;
  spec.rotation_deg = 3;
  spec.exposure_s = 0.002;
  spec.supersample = 2;
  return render_print_sequence(spec, print, marks);
}

// The capture's own choice of settings on the first frame, keeping only tracks over the whole
// sequence.
CaptureParams whole_sequence_tracks(const PrintSequence& seq) {
  CaptureParams params =
      with_choice({}, choose_capture_settings(seq.frames[0], seq.spec.px_per_mm));
  params.min_track_frames = seq.spec.frame_count;
  return params;
}

// The windows' deformation at the speed of touch, where the motion curves across each window:
// corrected for that like the positions, its share lowers the strain error there too.
TEST(RealPrintStrain, HeldOutPrintsFastSceneGainsFromTheWindowsCorrectedDeformation) {
  for (const char* nn : {"12", "14"}) {
    SCOPED_TRACE(fmt::format("print {}", nn));
    const PrintSequence seq = fast_scene(nn, 25, 16);
    const auto [ours, positions] = scored_against(
        seq, whole_sequence_tracks(seq), [](CaptureParams& p) { p.window_gradient_share = 0; },
        fmt::format("print {}, 8 % at 25 mm/s", nn), "positions alone");
    EXPECT_GT(ours.rms_truth, 0.01);  // or this is not the fast scene
    EXPECT_LT(ours.rms_error, positions.rms_error);
    EXPECT_GT(ours.correlation, positions.correlation);
  }
}

// At the speed of touch: a strain wave of 8 % crossing at 25 mm/s, filmed at 60 Hz with a 2 ms
// exposure by a camera that integrates each pixel's area, while the finger slides at 2.5 mm/s
// and turns by 3 degrees. About 1.5 px of motion and 3 % of strain change a frame: a track's
// first-frame window no longer matches after a few frames.
TEST(RealPrintStrain, HeldOutPrintsHoldAtTheSpeedOfTouch) {
  for (const char* nn : {"12", "14"}) {
    SCOPED_TRACE(fmt::format("print {}", nn));
    const PrintSequence seq = fast_scene(nn, 25, 16);
    const PrintWarpSpec& spec = seq.spec;
    const GroundTruth truth = ground_truth_of(seq);

    const CaptureParams params = whole_sequence_tracks(seq);
    const Evaluation ours = strain_scored(seq, params);
    LucasKanadeParams lk_params;
    lk_params.min_track_frames = spec.frame_count;
    const Evaluation lk = evaluate_strain(
        strain_from_tracks(track_lucas_kanade(seq.frames, seq.calibration, lk_params),
                           spec.frame_count, seq.calibration, 60, 1, params.max_edge_ratio),
        truth);
    std::printf(
        "print %s fast wave: ours tracked %.0f rms %.5f corr %.4f; Lucas-Kanade tracked %.0f rms "
        "%.5f corr %.4f (true strain rms %.5f)\n",
        nn, ours.median_tracked_points, ours.rms_error, ours.correlation, lk.median_tracked_points,
        lk.rms_error, lk.correlation, ours.rms_truth);
    // The frame-to-frame strain must be large, or this is not the fast scene.
    EXPECT_GT(ours.rms_truth, 0.008);
    EXPECT_GE(ours.median_tracked_points, 150);
    EXPECT_LE(ours.rms_error, 0.0025);
    EXPECT_GE(ours.correlation, 0.96);
    EXPECT_LT(ours.rms_error, lk.rms_error);
    EXPECT_GT(ours.correlation, lk.correlation);
  }
}

// Faster than touch is usually explored: the fast scene's wave crossing at 70 mm/s, still at
// 60 Hz. The skin moves up to 4.4 px a frame and its motion turns by more than a radian of the
// wave's phase from one frame to the next, so a track's own last step predicts its next one
// badly; where the alignment from there fails, its neighbours' motion in the same frame must
// carry it. The strain target scales with the true strain: the fast scene allows 0.0025 at
// about 0.020 RMS, an eighth of it. Without the neighbours (neighbour_rounds = 0) most tracks
// ended within a few frames.
TEST(RealPrintStrain, HeldOutPrintsHoldAtThreeTimesTheSpeedOfTouch) {
  for (const char* nn : {"12", "14"}) {
    SCOPED_TRACE(fmt::format("print {}", nn));
    const PrintSequence seq = fast_scene(nn, 70, 20);
    const auto [ours, own] = scored_against(
        seq, whole_sequence_tracks(seq),
        [](CaptureParams& p) { p.refinement.neighbour_rounds = 0; },
        fmt::format("print {} at 70 mm/s", nn), "each track on its own");
    EXPECT_GT(ours.rms_truth, 0.035);
    EXPECT_GE(ours.median_tracked_points, 150);
    EXPECT_LE(ours.rms_error, ours.rms_truth / 8);
    EXPECT_GE(ours.correlation, 0.96);
    // The case this guards: without the neighbours the tracker fails here.
    EXPECT_TRUE(own.median_tracked_points < 150 || own.rms_error > own.rms_truth / 8);
  }
}

// Twice the speed of touch, 50 mm/s at 60 Hz: every track is kept, but an affine window finds
// the weighted mean of the skin's motion across it, which on the curved motion of a 3 mm wave
// falls short of the landmark's own by M k^2 / 2 = 7 % (M the window weights' second moment) and
// shrinks the measured strain by as much: 0.0026 of error at this scene's true 0.037, which
// alone passes the fast scene's target of 0.0025. Corrected from the curvature of the
// neighbouring tracks' motion, that part goes and the error is the positions' noise (about
// 0.0022 if the rest is 0.0034): a cut of at least a fifth.
TEST(RealPrintStrain, HeldOutPrintsCorrectTheWindowsCurvatureBiasAtTwiceTheSpeedOfTouch) {
  for (const char* nn : {"12", "14"}) {
    SCOPED_TRACE(fmt::format("print {}", nn));
    const PrintSequence seq = fast_scene(nn, 50, 20);
    const auto [ours, plain] = scored_against(
        seq, whole_sequence_tracks(seq),
        [](CaptureParams& p) { p.refinement.curvature_correction = false; },
        fmt::format("print {} at 50 mm/s", nn), "uncorrected");
    EXPECT_GT(ours.rms_truth, 0.03);
    EXPECT_GE(ours.median_tracked_points, 150);
    EXPECT_GE(ours.correlation, 0.96);
    EXPECT_LE(ours.rms_error, 0.8 * plain.rms_error);
    // The case this guards: uncorrected, the fast scene's target fails here.
    EXPECT_GT(plain.rms_error, 0.0025);
  }
}

// The neighbours' rounds and the curvature correction read only what earlier rounds and frames
// settled, so the tracks are the same on one worker as on three.
TEST(RealPrintStrain, FastMotionTracksDoNotDependOnTheWorkerCount) {
  const PrintSequence seq = fast_scene("12", 70, 12);
  CaptureParams params = whole_sequence_tracks(seq);
  params.threads = 1;
  const auto one = tracks_of(measure_strain(seq.frames, seq.calibration, 60, params));
  params.threads = 3;
  const auto three = tracks_of(measure_strain(seq.frames, seq.calibration, 60, params));
  ASSERT_GE(one.size(), 150u);
  ASSERT_EQ(one.size(), three.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].first_frame, three[i].first_frame);
    EXPECT_EQ(one[i].x_px, three[i].x_px);
    EXPECT_EQ(one[i].y_px, three[i].y_px);
  }
}

}  // namespace
}  // namespace tactile::capture
