#pragma once
// Skin strain from tracked landmarks: Delaunay triangulation of the landmarks tracked from one
// frame into a later one, and the relative length change of each edge.

#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "tactile/capture/features.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/track.hpp"

namespace tactile::capture {

inline FeatureParams pores_only() {
  FeatureParams p;
  p.find_minutiae = false;
  return p;
}

// Where landmarks are followed by aligning the image around them, each alignment window also
// measures the skin's deformation across it (Track::gradient, corrected like the positions for
// motion that curves across the window). An edge's length change carried by the mean
// deformation of the windows at its two ends is a second measurement, its noise only partly
// shared with that of the two positions; this share of it is blended into each edge's strain.
// Chosen on tuning prints 01, 03 and 07: without the gradients' curvature correction, shares
// 0.2 / 0.3 / 0.4 / 0.5 raised the 1 % wave's correlation on print 01 from 0.9626 to 0.9660 /
// 0.9669 / 0.9674 / 0.9672 and took the fast scene's error (8 % at 25 mm/s) from 0.00167 to
// 0.00160 / 0.00163 / 0.00171 / 0.00182; with it, shares 0.3 / 0.4 / 0.5 / 0.6 gave 0.9673 /
// 0.9678 / 0.9678 / 0.9673 and 0.00150 / 0.00152 / 0.00157 / 0.00165. A window's deformation is
// still its weighted mean where the motion changes faster than a quadratic across it, so more
// of it would bias the strain of fast, curved motion.
inline constexpr double kWindowGradientShare = 0.3;

struct CaptureParams {
  // Pores only by default: the first-version minutiae (no syntactic repair yet) include bridge
  // and spur artefacts whose flicker between frames causes wrong matches; on the synthetic bump
  // they raised the consecutive-frame strain RMS error from 0.0006 to 0.015.
  FeatureParams features = pores_only();
  double match_radius_mm = 0.3;
  Assignment assignment = Assignment::greedy;
  // Shortest track linked from detections; with refinement, refinement.min_frames instead.
  int min_track_frames = kMinTrackFrames;
  int max_gap_frames = 2;
  int smoothing_half_window = 3;
  // Tracking by alignment against the images (AlignmentTracker), before smoothing.
  // Off by default: the paper's pore blobs have precise centres (see choose_capture_settings).
  bool refine = false;
  RefineParams refinement;
  int span_frames = 1;  // strain between frame i and frame i + span_frames
  // Edges longer than this multiple of the frame's median edge are hull slivers, not skin.
  double max_edge_ratio = 3.0;
  int threads = 0;  // workers (frames, tracks, triangulations in parallel); 0 = one per core
  // With refinement, landmarks are detected only on the first frame and then every this many
  // frames, or sooner when a fifth of the tracks have ended since the last detection; between
  // detections they are followed by alignment alone (AlignmentTracker).
  int redetect_every_frames = 30;
  // Share of each edge's strain measured by the alignment windows' deformation (0 = the edge's
  // end positions alone).
  double window_gradient_share = kWindowGradientShare;
  // Landmarks already found on the first frame with `features` (choose_capture_settings finds
  // them while choosing): used instead of detecting that frame again. Empty: detect it.
  std::vector<Feature> first_frame_features;
  // Measure where the skin touches in every frame as it is read (contact_map.hpp): the movie
  // gets its contact map, and where the skin slides through the view the tracks that stood at
  // or beside skin out of contact take no part in choosing the smoothing (their motion there is
  // the rim's, not the strain's). Off: no map, as a bench that times the tracking wants.
  bool measure_contact = false;
};

// Triangulates `from` (millimetre positions) and measures each edge at `to` (same order and
// track ids). Edges longer than max_edge_ratio x the median are dropped, and with them the
// triangles they bound. Fills edges and triangles; the caller sets frames and points.
void triangulate_strain(const std::vector<TrackedPoint>& from, const std::vector<TrackedPoint>& to,
                        double max_edge_ratio, std::vector<StrainEdge>& edges,
                        std::vector<StrainTriangle>& triangles);

using TracksById = std::unordered_map<std::int32_t, const Track*>;

// Blends into each edge of `frame` whose two tracks carry deformation gradients (Track::gradient)
// the length change that the mean of those gradients gives it: rel_change becomes (1 - share) x
// the positions' + share x the gradients', and length_to_mm follows it.
void blend_window_gradients(StrainFrame& frame, const TracksById& tracks,
                            const Calibration& calibration, double share);

// Strain movie from tracks already made: one StrainFrame per frame pair (i, i + span), the
// frames triangulated on `threads` workers (0: one per core), with blend_window_gradients
// where the tracks carry gradients.
StrainMovie strain_from_tracks(const std::vector<Track>& tracks, int camera_frame_count,
                               const Calibration& calibration, double frame_rate_hz,
                               int span_frames, double max_edge_ratio, int threads = 0,
                               double window_gradient_share = kWindowGradientShare);

// Settings that fit the image, chosen on its first frame: the pore detector that finds more
// pores there, and refinement with it when that is the ridge-blob detector. The paper's blobs
// are clean bright discs whose grey-level centres are precise (on the synthetic scenes
// refinement made the strain error worse); the ridge-blob detector's centres on real prints
// move with noise and the ridge beside the pore, and refinement cuts their strain error
// several-fold. Measured figures: docs/capture-models.md.
inline bool refinement_for(PoreDetector detector) {
  return detector == PoreDetector::ridge_blob;
}
// The trajectory smoothing that goes with refinement or without it. Refined positions carry
// independent errors from frame to frame, so a longer fit averages more of them; but a longer
// fit also flattens strain that changes within it, so with refinement this is the longest
// window tried, and the tracks themselves choose (smoothing_that_fits, with the falling weights
// of RefineParams::smoothing_kernel).
inline int smoothing_half_window_for(bool refine) {
  return refine ? 16 : CaptureParams{}.smoothing_half_window;
}

struct CaptureChoice {
  PoreDetector detector = PoreDetector::paper;
  bool refine = false;
  int smoothing_half_window = smoothing_half_window_for(false);
  int paper_pores = 0;  // pores each detector found on the frame
  int ridge_blob_pores = 0;
  std::vector<Feature> first_frame_features;  // what the chosen detector found there
};
CaptureChoice choose_capture_settings(const GrayImage& first_frame, double px_per_mm,
                                      const FeatureParams& base = pores_only());
// `params` with the choice's detector, refinement, smoothing and first-frame landmarks (which
// are right for `params.features` = pores_only() with the chosen detector, as here).
CaptureParams with_choice(CaptureParams params, const CaptureChoice& choice);

// Fills `frame` with the next frame and returns true, or returns false after the last one.
using FrameSource = std::function<bool(GrayImage& frame)>;
using CaptureProgress = std::function<void(const std::string& stage, int done, int total)>;

// The whole pipeline: extract -> match and track -> strain. `progress` is called with the stage
// name ("extract", "track", "strain") and counts.
StrainMovie measure_strain(const std::vector<GrayImage>& frames, const Calibration& calibration,
                           double frame_rate_hz, const CaptureParams& params = {},
                           const CaptureProgress& progress = {});

// The same on frames taken one at a time: at most a few frames (one per worker) are held at
// once, whatever the sequence's length. `expected_frames` is for progress only (0: unknown).
StrainMovie measure_strain(const FrameSource& next_frame, const Calibration& calibration,
                           double frame_rate_hz, const CaptureParams& params,
                           const CaptureProgress& progress = {}, int expected_frames = 0);

}  // namespace tactile::capture
