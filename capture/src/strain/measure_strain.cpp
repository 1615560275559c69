#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>

#include <fmt/format.h>

#include "tactile/capture/strain.hpp"
#include "tactile/common/parallel_for.hpp"

namespace tactile::capture {

StrainMovie strain_from_tracks(const std::vector<Track>& tracks, int camera_frame_count,
                               const Calibration& calibration, double frame_rate_hz,
                               int span_frames, double max_edge_ratio) {
  if (span_frames < 1) throw std::invalid_argument("span_frames must be >= 1");
  if (!(frame_rate_hz > 0)) throw std::invalid_argument("frame_rate_hz must be > 0");
  StrainMovie movie;
  movie.frame_rate_hz = frame_rate_hz;
  movie.span_frames = span_frames;
  movie.camera_frame_count = camera_frame_count;
  movie.calibration = calibration;
  const PointMm corner0 = to_mm(calibration, 0, 0);
  const PointMm corner1 =
      to_mm(calibration, calibration.image_width_px - 1.0, calibration.image_height_px - 1.0);
  movie.field_width_mm = std::abs(corner1.x_mm - corner0.x_mm);
  movie.field_height_mm = std::abs(corner1.y_mm - corner0.y_mm);

  auto point_of = [&](const Track& t, int frame) {
    const auto k = static_cast<std::size_t>(frame - t.first_frame);
    const PointMm mm = to_mm(calibration, t.x_px[k], t.y_px[k]);
    return TrackedPoint{t.id, frame, t.type, t.x_px[k], t.y_px[k], mm.x_mm, mm.y_mm};
  };
  for (const auto& t : tracks) {
    for (int f = t.first_frame; f <= t.last_frame(); ++f) movie.tracks.push_back(point_of(t, f));
  }
  for (int from = 0; from + span_frames < camera_frame_count; ++from) {
    StrainFrame sf;
    sf.frame_from = from;
    sf.frame_to = from + span_frames;
    sf.t_s = sf.frame_to / frame_rate_hz;
    for (const auto& t : tracks) {
      if (t.first_frame <= sf.frame_from && t.last_frame() >= sf.frame_to) {
        sf.points_from.push_back(point_of(t, sf.frame_from));
        sf.points_to.push_back(point_of(t, sf.frame_to));
      }
    }
    triangulate_strain(sf.points_from, sf.points_to, max_edge_ratio, sf.edges, sf.triangles);
    movie.frames.push_back(std::move(sf));
  }
  return movie;
}

CaptureChoice choose_capture_settings(const GrayImage& first_frame, double px_per_mm,
                                      const FeatureParams& base) {
  auto pores_with = [&](PoreDetector detector) {
    FeatureParams p = base;
    p.pore_detector = detector;
    p.find_minutiae = false;
    const auto found = extract_features(first_frame, px_per_mm, p);
    return static_cast<int>(std::count_if(
        found.begin(), found.end(), [](const Feature& f) { return f.type == FeatureType::pore; }));
  };
  CaptureChoice choice;
  choice.paper_pores = pores_with(PoreDetector::paper);
  choice.ridge_blob_pores = pores_with(PoreDetector::ridge_blob);
  if (choice.ridge_blob_pores > choice.paper_pores) choice.detector = PoreDetector::ridge_blob;
  choice.refine = refinement_for(choice.detector);
  choice.smoothing_half_window = smoothing_half_window_for(choice.refine);
  return choice;
}

CaptureParams with_choice(CaptureParams params, const CaptureChoice& choice) {
  params.features.pore_detector = choice.detector;
  params.refine = choice.refine;
  params.smoothing_half_window = choice.smoothing_half_window;
  return params;
}

StrainMovie measure_strain(
    const std::vector<GrayImage>& frames, const Calibration& calibration, double frame_rate_hz,
    const CaptureParams& params,
    const std::function<void(const std::string& stage, int done, int total)>& progress) {
  if (frames.empty()) throw std::invalid_argument("measure_strain: no frames");
  if (!(calibration.mm_per_px > 0)) {
    throw std::invalid_argument("measure_strain: calibration has no positive mm_per_px");
  }
  for (std::size_t i = 1; i < frames.size(); ++i) {
    if (frames[i].width_px != frames[0].width_px || frames[i].height_px != frames[0].height_px) {
      throw std::invalid_argument(fmt::format(
          "measure_strain: frame {} is {}x{} px, frame 0 is "
          "{}x{} px",
          i, frames[i].width_px, frames[i].height_px, frames[0].width_px, frames[0].height_px));
    }
  }
  if ((calibration.image_width_px != 0 && calibration.image_width_px != frames[0].width_px) ||
      (calibration.image_height_px != 0 && calibration.image_height_px != frames[0].height_px)) {
    throw std::invalid_argument(fmt::format(
        "measure_strain: the calibration is for {}x{} px images but the frames are {}x{} px",
        calibration.image_width_px, calibration.image_height_px, frames[0].width_px,
        frames[0].height_px));
  }
  Calibration cal = calibration;
  if (cal.image_width_px == 0) cal.image_width_px = frames[0].width_px;
  if (cal.image_height_px == 0) cal.image_height_px = frames[0].height_px;

  const int n = static_cast<int>(frames.size());
  const double px_per_mm = 1.0 / cal.mm_per_px;
  std::vector<std::vector<Feature>> features(frames.size());
  // Frames are independent. Progress is reported under a lock (the callback need not be
  // thread-safe), in the order frames finish.
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  parallel_for(frames.size(), worker_count(params.threads), [&](std::size_t i) {
    features[i] = extract_features(frames[i], px_per_mm, params.features);
    const int finished = ++done;
    if (progress) {
      const std::lock_guard lock(progress_mutex);
      progress("extract", finished, n);
    }
  });
  if (progress) progress("extract", done.load(), n);

  TrackParams tp;
  tp.match_radius_mm = params.match_radius_mm;
  tp.assignment = params.assignment;
  // Refined tracks are followed by the image, so a detection track need only be long enough to
  // show that it is a landmark.
  tp.min_track_frames = params.refine
                            ? std::min(params.min_track_frames, params.refinement.min_seed_frames)
                            : params.min_track_frames;
  if (params.refine) tp.max_jump_mm = std::max(tp.max_jump_mm, params.refinement.seed_max_jump_mm);
  tp.max_gap_frames = params.max_gap_frames;
  tp.smoothing_half_window = params.refine ? 0 : params.smoothing_half_window;
  std::vector<Track> tracks = track_features(features, cal, tp);
  if (progress) progress("track", 1, 1);
  if (params.refine) {
    const std::vector<Track> detected =
        params.refinement.fast_window_mm > 0 ? tracks : std::vector<Track>{};
    refine_tracks(frames, tracks, px_per_mm, params.refinement, params.threads);
    int half_window = smoothing_that_fits(tracks, params.smoothing_half_window,
                                          params.refinement.max_smoothing_residual_px);
    // Motion that a smoother over a few frames would flatten means the strain changes fast,
    // and then across the window too: a smaller window follows that non-affine deformation
    // (on still patterns the larger one averages more noise away).
    if (half_window == 0 && params.smoothing_half_window > 0 &&
        params.refinement.fast_window_mm > 0 &&
        params.refinement.fast_window_mm < params.refinement.window_mm) {
      RefineParams fast = params.refinement;
      fast.window_mm = fast.fast_window_mm;
      tracks = detected;
      refine_tracks(frames, tracks, px_per_mm, fast, params.threads);
      half_window = smoothing_that_fits(tracks, params.smoothing_half_window,
                                        params.refinement.max_smoothing_residual_px);
    }
    smooth_tracks(tracks, half_window);
    if (progress) progress("refine", 1, 1);
  }

  StrainMovie movie =
      strain_from_tracks(tracks, n, cal, frame_rate_hz, params.span_frames, params.max_edge_ratio);
  if (progress) progress("strain", 1, 1);
  return movie;
}

}  // namespace tactile::capture
