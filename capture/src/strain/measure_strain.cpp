#include <algorithm>
#include <future>
#include <optional>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "tactile/capture/capture.hpp"
#include "tactile/capture/contact_map.hpp"
#include "tactile/capture/contact_strain.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/common/provenance.hpp"

namespace tactile::capture {

StrainMovie strain_from_tracks(const std::vector<Track>& tracks, int camera_frame_count,
                               const Calibration& calibration, double frame_rate_hz,
                               int span_frames, double max_edge_ratio, int threads,
                               double window_gradient_share) {
  if (span_frames < 1) throw std::invalid_argument("span_frames must be >= 1");
  if (!(window_gradient_share >= 0 && window_gradient_share <= 1)) {
    throw std::invalid_argument("window_gradient_share must be 0 to 1");
  }
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
  TracksById by_id;
  for (const auto& t : tracks) by_id.emplace(t.id, &t);
  // Each frame's triangulation is its own: frames in parallel.
  movie.frames.resize(static_cast<std::size_t>(std::max(0, camera_frame_count - span_frames)));
  parallel_for(movie.frames.size(), worker_count(threads), [&](std::size_t k) {
    const int from = static_cast<int>(k);
    StrainFrame& sf = movie.frames[k];
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
    blend_window_gradients(sf, by_id, calibration, window_gradient_share);
  });
  return movie;
}

CaptureChoice choose_capture_settings(const GrayImage& first_frame, double px_per_mm,
                                      const FeatureParams& base) {
  auto pores_with = [&](PoreDetector detector) {
    FeatureParams p = base;
    p.pore_detector = detector;
    p.find_minutiae = false;
    // The paper's rule takes a fifteenth of the ridge-blob detector's time: the core it frees
    // joins the ridge-blob filtering (the choice already uses every core).
    p.ridge_blob.threads = worker_count(0);
    return extract_features(first_frame, px_per_mm, p);
  };
  auto pore_count = [](const std::vector<Feature>& found) {
    return static_cast<int>(std::count_if(
        found.begin(), found.end(), [](const Feature& f) { return f.type == FeatureType::pore; }));
  };
  std::vector<Feature> paper, ridge_blob;
  // The two detectors side by side: the choice is made before any frame is tracked.
  parallel_for(2, worker_count(0), [&](std::size_t k) {
    if (k == 0) {
      paper = pores_with(PoreDetector::paper);
    } else {
      ridge_blob = pores_with(PoreDetector::ridge_blob);
    }
  });
  CaptureChoice choice;
  choice.paper_pores = pore_count(paper);
  choice.ridge_blob_pores = pore_count(ridge_blob);
  if (choice.ridge_blob_pores > choice.paper_pores) choice.detector = PoreDetector::ridge_blob;
  choice.refine = refinement_for(choice.detector);
  choice.smoothing_half_window = smoothing_half_window_for(choice.refine);
  choice.first_frame_features =
      std::move(choice.detector == PoreDetector::ridge_blob ? ridge_blob : paper);
  return choice;
}

CaptureParams with_choice(CaptureParams params, const CaptureChoice& choice) {
  params.features.pore_detector = choice.detector;
  params.refine = choice.refine;
  params.smoothing_half_window = choice.smoothing_half_window;
  params.first_frame_features = choice.first_frame_features;
  return params;
}

namespace {

// Frames must all have the size of the first, which the calibration (when it names one) fixes.
void check_frame_size(const GrayImage& frame, int index, const GrayImage& first,
                      const Calibration& calibration) {
  if (index > 0 && (frame.width_px != first.width_px || frame.height_px != first.height_px)) {
    throw std::invalid_argument(
        fmt::format("measure_strain: frame {} is {}x{} px, frame 0 is {}x{} px", index,
                    frame.width_px, frame.height_px, first.width_px, first.height_px));
  }
  if (index == 0) {
    check_calibration_fits(calibration, frame.width_px, frame.height_px, "measure_strain",
                           "the first frame");
  }
}

std::vector<Feature> pores_in(const GrayImage& frame, double px_per_mm,
                              const FeatureParams& params) {
  return extract_features(frame, px_per_mm, params);
}

// Detection on every frame, frames in parallel (a batch of one per worker at a time), then
// matching and linking of the detections.
std::vector<Track> tracks_from_detections(const FrameSource& next_frame, GrayImage& first,
                                          const Calibration& cal, const CaptureParams& params,
                                          const CaptureProgress& progress, int expected,
                                          int& frame_count) {
  const double px_per_mm = 1.0 / cal.mm_per_px;
  const int workers = worker_count(params.threads);
  std::vector<std::vector<Feature>> features;
  const GrayImage size_of_first{first.width_px, first.height_px, {}};
  std::vector<GrayImage> batch;
  batch.push_back(std::move(first));
  for (bool more = true;;) {
    while (more && static_cast<int>(batch.size()) < 2 * workers) {
      GrayImage next;
      more = next_frame(next);
      if (!more) break;
      check_frame_size(next, static_cast<int>(features.size() + batch.size()), size_of_first, cal);
      batch.push_back(std::move(next));
    }
    if (batch.empty()) break;
    const std::size_t base = features.size();
    features.resize(base + batch.size());
    parallel_for(batch.size(), workers, [&](std::size_t i) {
      features[base + i] = base + i == 0 && !params.first_frame_features.empty()
                               ? params.first_frame_features
                               : pores_in(batch[i], px_per_mm, params.features);
    });
    batch.clear();
    if (progress) progress("extract", static_cast<int>(features.size()), expected);
  }
  frame_count = static_cast<int>(features.size());
  TrackParams tp;
  tp.match_radius_mm = params.match_radius_mm;
  tp.assignment = params.assignment;
  tp.min_track_frames = params.min_track_frames;
  tp.max_gap_frames = params.max_gap_frames;
  tp.smoothing_half_window = params.smoothing_half_window;
  std::vector<Track> tracks = track_features(features, cal, tp);
  if (progress) progress("track", 1, 1);
  return tracks;
}

// Detection on the first frame and when tracks run short; alignment in between.
std::vector<Track> tracks_by_alignment(const FrameSource& next_frame, GrayImage& first,
                                       const Calibration& cal, const CaptureParams& params,
                                       const CaptureProgress& progress, int expected,
                                       int& frame_count, RefineStats& stats) {
  const double px_per_mm = 1.0 / cal.mm_per_px;
  // --min-track below the alignment's own shortest track lowers it too (a short sequence asked
  // for short tracks); above it, the alignment keeps its own, as it did by default.
  RefineParams refinement = params.refinement;
  refinement.min_frames = std::min(refinement.min_frames, std::max(2, params.min_track_frames));
  AlignmentTracker tracker(px_per_mm, refinement, params.threads);
  // A re-detection holds up the frame's alignment: all workers detect.
  FeatureParams detection = params.features;
  detection.ridge_blob.threads = worker_count(params.threads);
  const GrayImage size_of_first{first.width_px, first.height_px, {}};
  GrayImage frame = std::move(first);
  int last_detection = 0, live_after_detection = 0;
  // The next frame is read (an image file decoded, a video frame decoded) on a thread of its
  // own while this one is aligned: reading is serial work, and the alignment leaves the cores
  // room for it between its parallel steps. The source is called once at a time, in order.
  const auto read_next = [&next_frame]() {
    std::optional<GrayImage> next(std::in_place);
    if (!next_frame(*next)) next.reset();
    return next;
  };
  for (int f = 0;; ++f) {
    auto ahead = std::async(std::launch::async, read_next);
    const bool due = f == 0 || f - last_detection >= params.redetect_every_frames;
    // A fifth of the tracks gone: landmarks have left the view or stopped matching their
    // first-frame neighbourhood.
    const bool short_of_tracks = 5 * tracker.live_tracks() < 4 * live_after_detection;
    // Where the view slides, new skin enters at one edge every frame: detect every frame (seeds
    // start tracks only where no live track is, so in practice in the entering band).
    const bool entering = tracker.sliding();
    if (f == 0 && !params.first_frame_features.empty()) {
      tracker.add_frame(frame, params.first_frame_features);
      live_after_detection = tracker.live_tracks();
    } else if (due || short_of_tracks || entering) {
      tracker.add_frame(frame, pores_in(frame, px_per_mm, detection));
      last_detection = f;
      live_after_detection = tracker.live_tracks();
    } else {
      tracker.add_frame(frame, {});
    }
    if (progress) progress("track", f + 1, expected);
    std::optional<GrayImage> next = ahead.get();
    if (!next) break;
    frame = std::move(*next);
    check_frame_size(frame, f + 1, size_of_first, cal);
  }
  frame_count = tracker.frames();
  return tracker.finish(&stats);
}

// A smoother over more frames than the motion stays smooth for would flatten it: smooth only as
// far as the tracks allow. Where the skin slides through the view, the tracks clear of skin out
// of contact choose (when the map has them: a quarter of the tracks at least), with the noise
// taken sliding_noise_scale times over (RefineParams says why).
void smooth_aligned_tracks(std::vector<Track>& tracks, const ContactMap& contact,
                           const CaptureParams& params, RefineStats& stats) {
  const bool sliding = stats.frames_in_view > 0;
  std::vector<Track> clear;
  if (sliding && contact.measured()) clear = tracks_clear_of_gaps(tracks, contact);
  const bool clear_choose = 4 * clear.size() >= tracks.size() && !clear.empty();
  const SmoothingKernel kernel = params.refinement.smoothing_kernel;
  stats.smoothing_half_window =
      smoothing_that_fits(clear_choose ? clear : tracks, params.smoothing_half_window,
                          params.refinement.max_smoothing_residual_px, kernel, params.threads,
                          sliding ? params.refinement.sliding_noise_scale : 1.0);
  smooth_tracks(tracks, stats.smoothing_half_window, kernel, params.threads);
  stats.smoothing_reason =
      !sliding ? std::string("chosen by the tracks' own noise")
               : fmt::format(
                     "chosen by {} of {} tracks ({}) from their own noise, taken {:g} "
                     "times over where the skin slides",
                     clear_choose ? clear.size() : tracks.size(), tracks.size(),
                     clear_choose ? "those clear of skin out of contact" : "all of them",
                     params.refinement.sliding_noise_scale);
}

}  // namespace

StrainMovie measure_strain(const FrameSource& next_frame, const Calibration& calibration,
                           double frame_rate_hz, const CaptureParams& params,
                           const CaptureProgress& progress, int expected_frames) {
  if (!(calibration.mm_per_px > 0)) {
    throw std::invalid_argument("measure_strain: calibration has no positive mm_per_px");
  }
  if (params.redetect_every_frames < 1) {
    throw std::invalid_argument("measure_strain: redetect_every_frames must be >= 1");
  }
  GrayImage first;
  if (!next_frame(first)) throw std::invalid_argument("measure_strain: no frames");
  check_frame_size(first, 0, first, calibration);
  Calibration cal = calibration;
  if (cal.image_width_px == 0) cal.image_width_px = first.width_px;
  if (cal.image_height_px == 0) cal.image_height_px = first.height_px;

  // Each frame's contact as it is read (the trackers read the frames once, in order).
  const double px_per_mm = 1.0 / cal.mm_per_px;
  const GrayImage size_of_first{first.width_px, first.height_px, {}};
  std::optional<ContactGrid> grid;
  std::vector<double> contrast;
  int read = 0;
  const auto measure_contact_of = [&](const GrayImage& frame) {
    check_frame_size(frame, read++, size_of_first, cal);
    const std::vector<double> cells = cell_ridge_contrast(frame, *grid, px_per_mm);
    contrast.insert(contrast.end(), cells.begin(), cells.end());
  };
  FrameSource with_contact;
  if (params.measure_contact) {
    grid = contact_grid(first.width_px, first.height_px, px_per_mm);
    measure_contact_of(first);
    with_contact = [&](GrayImage& frame) {
      if (!next_frame(frame)) return false;
      measure_contact_of(frame);
      return true;
    };
  }
  const FrameSource& source = params.measure_contact ? with_contact : next_frame;

  int n = 0;
  RefineStats stats;
  std::vector<Track> tracks =
      params.refine
          ? tracks_by_alignment(source, first, cal, params, progress, expected_frames, n, stats)
          : tracks_from_detections(source, first, cal, params, progress, expected_frames, n);
  ContactMap contact = grid ? contact_map(*grid, std::move(contrast)) : ContactMap{};
  if (params.refine) {
    smooth_aligned_tracks(tracks, contact, params, stats);
    if (progress) progress("refine", 1, 1);
  }
  StrainMovie movie =
      strain_from_tracks(tracks, n, cal, frame_rate_hz, params.span_frames, params.max_edge_ratio,
                         params.threads, params.window_gradient_share);
  movie.contact = std::move(contact);
  // The settings that decide what is measured; the frames' file is the caller's to name.
  nlohmann::json settings = {
      {"frame_rate_hz", frame_rate_hz},
      {"mm_per_px", cal.mm_per_px},
      {"pore_detector", to_string(params.features.pore_detector)},
      {"refine", params.refine},
      {"smoothing_half_window", params.smoothing_half_window},
      {"span_frames", params.span_frames},
      {"min_track_frames", params.min_track_frames},
      {"assignment", to_string(params.assignment)},
      {"match_radius_mm", params.match_radius_mm},
      // Only aligned tracks carry the windows' deformation.
      {"window_gradient_share", params.refine ? params.window_gradient_share : 0.0}};
  if (params.refine) {
    // What the sequence showed and the shortest track it led to (fewer frames than asked where
    // the skin slides through the view and stays in it for fewer).
    settings["view_motion_px_per_frame"] = stats.view_motion_px;
    settings["frames_in_view"] = stats.frames_in_view;
    settings["min_track_frames_used"] = stats.min_frames;
    settings["smoothing_half_window_used"] = stats.smoothing_half_window;
    settings["smoothing_reason"] = stats.smoothing_reason;
    settings["min_track_reason"] = stats.frames_in_view > 0
                                       ? fmt::format(
                                             "the view slides {:.1f} px a frame, so skin stays in "
                                             "view for {:.1f} frames; tracks of half of that "
                                             "(at least 3) kept",
                                             stats.view_motion_px, stats.frames_in_view)
                                       : std::string("still contact: the alignment's own");
  }
  movie.provenance = make_provenance({}, "capture", settings.dump());
  if (progress) progress("strain", 1, 1);
  return movie;
}

StrainMovie measure_strain(const std::vector<GrayImage>& frames, const Calibration& calibration,
                           double frame_rate_hz, const CaptureParams& params,
                           const CaptureProgress& progress) {
  if (frames.empty()) throw std::invalid_argument("measure_strain: no frames");
  std::size_t next = 0;
  return measure_strain(
      [&](GrayImage& frame) {
        if (next == frames.size()) return false;
        frame = frames[next++];
        return true;
      },
      calibration, frame_rate_hz, params, progress, static_cast<int>(frames.size()));
}

}  // namespace tactile::capture
