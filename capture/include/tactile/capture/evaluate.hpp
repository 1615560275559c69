#pragma once
// Accuracy of a measured strain movie against the exact ground truth of a synthetic sequence
// (`tactile synth` folder: scene.json + landmarks.csv).

#include <cstdint>
#include <filesystem>
#include <vector>

#include <optional>

#include "tactile/capture/print_warp.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/synth.hpp"

namespace tactile::capture {

struct GroundTruth {
  SceneSpec spec;  // a synthetic scene (scene.json format tactile-synthetic-scene), unless warp
  Calibration calibration;               // the true px -> mm map of the synthetic camera
  std::vector<TruthLandmark> landmarks;  // every landmark in view and in contact, every frame
  std::optional<PrintWarpSpec> warp;     // a warped real print (format tactile-print-warp)
};

// The truth of a rendered real-print sequence, as read_ground_truth reads it from its folder.
GroundTruth ground_truth_of(const PrintSequence& sequence);

// Frames of the truth's sequence, and the true relative length change of a segment (image
// millimetres at frame_from, seen again at frame_to), whichever kind of truth it is.
int truth_frame_count(const GroundTruth& truth);
double truth_rel_change(const GroundTruth& truth, PointMm a_from, PointMm b_from, int frame_from,
                        int frame_to);

// Reads DIR/scene.json and DIR/landmarks.csv. Throws tactile::FormatError naming the file and
// the problem (missing, not JSON, another format, missing or mistyped fields, bad CSV rows).
GroundTruth read_ground_truth(const std::filesystem::path& dir);

struct FrameEvaluation {
  std::int32_t frame_from = 0;
  std::int32_t frame_to = 0;
  std::int32_t edges = 0;
  double rms_error = 0;  // RMS of measured - true relative edge-length change (0 if no edges)
  double rms_truth = 0;  // RMS of the true relative change on the same edges
  std::int32_t tracked_points = 0;   // tracked landmarks at frame_from
  std::int32_t truth_landmarks = 0;  // true landmarks in view and in contact at frame_from
  // Where the skin lifts off (Evaluation::has_gap): the edges in full contact, and their error.
  std::int32_t edges_in_contact = 0;
  double rms_error_in_contact = 0;
};

struct Evaluation {
  std::vector<FrameEvaluation> frames;
  std::int64_t edges = 0;
  double rms_error = 0;  // over every edge of every frame
  double rms_truth = 0;
  // Pearson correlation of measured and true relative changes over every edge (0 when either
  // has no spread, e.g. a rigid motion whose true strain is zero everywhere).
  double correlation = 0;
  // Localisation: each tracked point against the nearest true landmark of its frame (any type)
  // within `match_bound_mm`; points with none are counted as unmatched.
  double match_bound_mm = 0.15;
  std::int64_t located_points = 0;
  std::int64_t unmatched_points = 0;
  double localisation_rms_mm = 0;
  double median_tracked_points = 0;  // per frame pair (tracked_points)
  double median_yield = 0;           // per frame: tracked_points / truth_landmarks
  std::int32_t track_count = 0;
  double median_track_frames = 0;
  double mean_track_frames = 0;
  // A scene whose skin lifts off and lands again (PrintWarpSpec::contact_loss > 0) or touches
  // in a patch smaller than the view (has_contact_patch): the same
  // figures over the edges whose two ends were in full contact at both frames (outside the gap
  // and its rim), and how many compared edges touched the gap, where no strain should be
  // reported (an end in less than half contact at either frame). Zero for other scenes.
  bool has_gap = false;
  std::int64_t edges_in_contact = 0;
  double rms_error_in_contact = 0;
  double correlation_in_contact = 0;
  std::int64_t edges_across_gap = 0;
  // Of edges_across_gap, those whose ends in less than half contact are all in a frame where a
  // gap first shows (less than half contact somewhere in the view, nowhere in the frame before):
  // there it is a spot smaller than a contact cell, which a causal tracker, seeing no later
  // frame, cannot tell from skin in contact.
  std::int64_t edges_across_gap_opening = 0;
  // The movie's contact map against the truth (has_gap, and a movie with a map): the cells at
  // least three quarters in or out of contact in the truth (sampled on a 4 x 4 grid), the
  // fraction of them the map got right, and the overlap of the cells out of contact (the truth's
  // and the map's, intersection over union; 1 when neither has any). Zero otherwise.
  std::int64_t contact_cells = 0;
  std::int64_t gap_cells = 0;  // of contact_cells, those out of contact in the truth
  double contact_agreement = 0;
  double gap_overlap = 0;
};

// True positions come from each point's pixel position through the true calibration, so a
// wrong calibration in the movie shows up as strain error. A movie with no frames or no edges
// gives zero counts (and zero RMS), not an error.
Evaluation evaluate_strain(const StrainMovie& movie, const GroundTruth& truth);

// DIR/evaluation_frames.csv (frame_from,frame_to,edges,rms_error,rms_truth,tracked_points,
// truth_landmarks) and DIR/evaluation_summary.csv (metric,value); creates DIR.
void write_evaluation_csv(const std::filesystem::path& dir, const Evaluation& evaluation);

}  // namespace tactile::capture
