#pragma once
// Frame-to-frame matching of landmarks and their trajectories.

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/common/names.hpp"

namespace tactile::capture {

// One-to-one matching of tracks to a frame's features: greedy by decreasing confidence, or
// optimal (maximum total confidence; Hungarian method on each group of competing candidates).
enum class Assignment { greedy, optimal };
inline constexpr std::array<Named<Assignment>, 2> kAssignmentNames = {{
    {Assignment::greedy, "greedy"},
    {Assignment::optimal, "optimal"},
}};
inline std::string to_string(Assignment a) {
  return name_in(kAssignmentNames, a);
}

// Shortest trajectory kept by default: the first paper rejected trajectories shorter than about
// 30 frames (half a second at 60 Hz) as spurious matches.
inline constexpr int kMinTrackFrames = 30;

struct TrackParams {
  Assignment assignment = Assignment::greedy;
  double match_radius_mm = 0.3;            // search radius around the predicted position
  int min_track_frames = kMinTrackFrames;  // shorter trajectories are rejected
  int max_gap_frames = 2;                  // a landmark may be missed this many frames in a row
  int smoothing_half_window = 3;           // local quadratic fit over 2h+1 frames; 0 = no smoothing
  // A position further than this from the straight-line motion of the 6 before it is a wrong
  // match (a landmark left contact and a neighbour was taken for it): the track is cut there.
  // Real motion deviates far less: 0.05 mm allows accelerations up to about 0.01 mm/frame^2.
  double max_jump_mm = 0.05;
};

// One landmark's trajectory: a position for every frame from first_frame on (frames where it
// was missed are interpolated).
struct Track {
  std::int32_t id = 0;
  FeatureType type = FeatureType::pore;
  std::int32_t first_frame = 0;
  std::vector<double> x_px;
  std::vector<double> y_px;
  // Where the landmark was followed by aligning the image around it (AlignmentTracker): for
  // every frame, the linear part of that alignment's affine warp, the skin's deformation
  // gradient across the window from first_frame (row-major: dx/dX, dx/dY, dy/dX, dy/dY, in
  // pixels). Empty where the tracker does not measure it.
  std::vector<std::array<double, 4>> gradient;

  std::int32_t last_frame() const {
    return first_frame + static_cast<std::int32_t>(x_px.size()) - 1;
  }
};

// Matches consecutive frames (same type, within match_radius_mm of the position predicted from
// the previous displacement, one-to-one, greedy by confidence = 1 - distance / radius, lowered
// by orientation disagreement for endings), links matches into tracks, cuts tracks at jumps,
// drops short tracks and smooths the rest. Kept tracks are numbered 0.. in order of first frame.
std::vector<Track> track_features(const std::vector<std::vector<Feature>>& features_per_frame,
                                  const Calibration& calibration, const TrackParams& params = {});

// How the local quadratic fit of a trajectory weighs the frames of its window: all alike, or
// falling with the distance t from the frame fitted as 1 - (t / (h + 1))^2 (Epanechnikov). For
// the same noise left, the falling weights flatten a changing motion less (the local fit's
// least squared error among weightings), so they go with the longer windows the tracks choose.
enum class SmoothingKernel { uniform, epanechnikov };

// Every track's positions smoothed by a local quadratic fit over 2 h + 1 frames (h <= 0: none),
// on `threads` workers (0: every core).
void smooth_tracks(std::vector<Track>& tracks, int half_window,
                   SmoothingKernel kernel = SmoothingKernel::uniform, int threads = 1);

// The smoothing window (half-window half_window, 14, 12, 10, 8, 7, 6, 5, 4, 3, none longer than
// half_window, or 0 for none) whose frame-to-frame changes between neighbouring tracks have the
// least error, as estimated from the tracks themselves: a longer window averages more of the
// trackers' noise, but flattens strain that changes within it. A window that moves the median
// track by more than max_residual_px (RMS) is not taken. The noise estimated from the tracks is
// taken noise_scale times over. On `threads` workers (0: every core).
int smoothing_that_fits(const std::vector<Track>& tracks, int half_window, double max_residual_px,
                        SmoothingKernel kernel = SmoothingKernel::uniform, int threads = 1,
                        double noise_scale = 1.0);

// The same choice for a smoothing that may only look back (causal_smoothing.hpp): a polynomial
// of `degree` (1 or 2) fitted to a track's last W positions and read at the last two, W one of
// kCausalWindows (or 0 for none), chosen by the same estimate of the error of the frame-to-frame
// changes between neighbouring tracks. Looking back, the fit lags a strain that changes within
// it, which the estimate sees as it sees the centred window's flattening. As there, a window
// that moves the median track's last position by more than max_residual_px (RMS) is not
// taken: the noise is measured by a centred smoother, and where the motion changes within a few
// frames that smoother takes some of it for noise. Tracks of fewer than kCausalChoiceFrames
// frames take no part; with fewer than 20 neighbour pairs the answer is 0.
inline constexpr std::array<int, 9> kCausalWindows = {4, 5, 6, 8, 10, 12, 16, 20, 24};
inline constexpr int kCausalChoiceFrames = 25;
int causal_smoothing_that_fits(const std::vector<Track>& tracks, int degree, double max_residual_px,
                               int threads = 1, double noise_scale = 1.0);

// Sub-pixel refinement against the images. A detected landmark gives identity and no drift but
// a noisy centre (a pore's grey-level centre moves with noise, blur and the ridge beside it);
// the image around it gives a precise displacement. Each track's neighbourhood in its first
// frame is the reference, and every later frame is aligned to it by an affine warp, started
// where the detected step puts the landmark. Measuring against one reference, not frame to
// frame, keeps the error of each position independent (chained steps add up their errors and
// the strain, a difference of positions, sees them all), and the affine warp lets the window
// follow the skin's stretch and rotation, which a translation-only window averages into its
// position. A track ends at the first frame the image does not confirm; tracks left shorter
// than min_frames are dropped, and the rest renumbered 0.. in their order.
struct RefineParams {
  // Reference window side (about two ridge periods). Larger averages more of the camera's
  // noise, smaller follows strain that changes across the skin: with the windows' deformation
  // blended into the strain and corrected for curvature, 0.8 rather than 0.7 took the 1 % wave's
  // correlation on tuning prints 01 / 07 from 0.9673 / 0.9637 to 0.9757 / 0.9712, for 0.00045 ->
  // 0.00049 on the 8 % wave and 0.00150 -> 0.00159 on the fast scene (print 01).
  double window_mm = 0.8;
  double min_correlation = 0.8;  // alignment's correlation coefficient that confirms a frame
  double max_distortion = 0.25;  // largest |entry| of the warp's linear part minus identity
  double max_offset_mm = 0.1;    // largest distance of a confirmed position from the detection
  int max_iterations = 40;       // of the alignment
  double stop_step_px = 1e-3;    // the alignment has converged when a step moves less
  // Alignment steps alternate between the window's even rows and its odd rows (each half a
  // whole window's cost) and end on the mean of the two halves' warps, which averages the
  // camera's noise over every row as a whole window does; false = whole-window steps (the first
  // on the even rows only), about a third more window work for the same precision.
  bool alternate_row_halves = true;
  double presmoothing_px = 0.6;  // Gaussian sigma applied to the frames before aligning
  int min_frames = 10;           // shortest refined track kept
  // Follow a track by the image alone past the frames where it was detected (to the end of the
  // sequence or until the image stops confirming it).
  bool follow_past_detections = true;
  // Where the image stops confirming a frame against the reference, try the last confirmed
  // frame as the new reference before ending the track.
  bool reanchor = true;
  double same_landmark_mm = 0.06;  // two tracks this close in a frame follow one landmark
  // Trajectories are smoothed only where the smoother moves the median track by at most this
  // (RMS): about twice the refined positions' noise.
  double max_smoothing_residual_px = 0.06;
  // The weights of that smoothing's local fits.
  SmoothingKernel smoothing_kernel = SmoothingKernel::epanechnikov;
  // Where the skin slides through the view, the trackers' noise as the smoothing's choice
  // estimates it (smoothing_that_fits) is taken this many times over. Sliding tracks are aligned
  // to a reference the skin moves away from as it crosses the strain, so their errors change
  // slowly from frame to frame, and the choice's estimate, made by a smoother that removes only
  // the fastest changes, reads short: against the exact warp on tuning prints 01-06 at 10 mm/s
  // it chose half-window 3 where 6 was best (docs/capture-models.md). Still contact keeps 1.
  double sliding_noise_scale = 2.0;
  // Streaming tracker (AlignmentTracker): where a track's own prediction fails, retry from its
  // confirmed neighbours' motion in the same frame (within neighbour_radius_mm), in up to
  // neighbour_rounds rounds (0 = never), when that start is neighbour_retry_px or more from the
  // one tried.
  int neighbour_rounds = 4;
  double neighbour_radius_mm = 1.0;
  double neighbour_retry_px = 0.5;
  // A confirmed position further than this from its neighbours' motion is checked again (0 =
  // never).
  double neighbour_check_px = 1.5;
  // Streaming tracker: each position corrected for the affine window's bias where the skin's
  // motion is curved across it (the weighted mean of the motion over the window, not its value
  // at the landmark), from a quadratic fit of the neighbouring tracks (within
  // neighbour_radius_mm).
  bool curvature_correction = true;
};

struct RefineStats {
  long steps = 0;    // frame-to-frame alignments tried
  long cut = 0;      // tracks ended early, where the image did not confirm a frame
  long dropped = 0;  // of which left shorter than min_frames, and removed
  long anchors = 0;  // references renewed on a later frame
  long thinned = 0;  // streaming tracker: tracks ended where they crowded older ones
  // Streaming tracker: the whole view's median motion per frame (pixels), the frames a point of
  // skin stays in view at that motion (0: the view does not slide) and the shortest track kept.
  double view_motion_px = 0;
  double frames_in_view = 0;
  int min_frames = 0;
  // The half-window (frames) of the smoothing the tracks were given after alignment, and what
  // chose it (said in the capture's provenance).
  int smoothing_half_window = 0;
  std::string smoothing_reason;
};

// Tracks are refined in parallel on `threads` workers (0 = one per core).
RefineStats refine_tracks(const std::vector<GrayImage>& frames, std::vector<Track>& tracks,
                          double px_per_mm, const RefineParams& params = {}, int threads = 0);

// Tracking by alignment alone, one frame at a time: landmarks detected in a frame (seeds) start
// tracks, and every later frame is aligned to each track's first-frame neighbourhood as in
// refine_tracks, started where the track's last step predicts it (constant velocity) instead of
// at a detection. Detection, the costly part on real prints, then runs only on the frames that
// seed tracks. A frame is confirmed as in refine_tracks, with the prediction in place of the
// detection (within max_offset_mm of it); a track ends at its first unconfirmed frame. Frames
// are taken one by one, so a sequence need not be held in memory.
class AlignmentTracker {
 public:
  // Tracks are aligned in parallel on `threads` workers (0 = one per core).
  AlignmentTracker(double px_per_mm, const RefineParams& params = {}, int threads = 0);
  ~AlignmentTracker();
  AlignmentTracker(const AlignmentTracker&) = delete;
  AlignmentTracker& operator=(const AlignmentTracker&) = delete;

  // Aligns the live tracks to `image` (the next frame), then starts a track at every seed (pixel
  // positions in this frame) further than half of max_offset_mm from every live track.
  void add_frame(const GrayImage& image, const std::vector<Feature>& seeds);
  // The same with seeds found on an earlier frame, `seeds_frame` (0 to frames(), the count
  // this frame will have): each is first carried to this frame by the motion of the live tracks
  // around it since then (by the whole view's where fewer than three are within
  // neighbour_radius_mm). A detector slower than the camera runs beside the tracker this way.
  void add_frame(const GrayImage& image, const std::vector<Feature>& seeds, int seeds_frame);
  int frames() const;
  int live_tracks() const;
  // From the next frame on, no track within `px` of an older live track (the younger ends, as
  // one the image stopped confirming) and no new track within `px` of a live one or of a seed
  // started before it; 0: every landmark the seeds give. A consumer that must keep up with a
  // camera trades the tracks' density for time this way. Throws std::invalid_argument for a
  // negative or non-finite px.
  void set_min_spacing_px(double px);
  // Whether the whole view moved into the last frame by more than an alignment may move from
  // its start (max_offset_mm): the skin slides through it and new skin enters every frame.
  bool sliding() const;
  // The live tracks followed into the last frame from the one before it, as tracks of those two
  // frames (positions in pixels and window gradients; first_frame is the tracker's count of
  // frames, less 2): what a causal consumer measures strain from, frame by frame. Each position
  // is corrected for the window's curvature bias as finish() corrects whole tracks, from the
  // neighbours' motion since the track's first step (its fit kept while it lives); no
  // smoothing, which needs later frames. Ids are the tracker's own (stable while a track lives),
  // not finish()'s renumbering.
  std::vector<Track> last_step();
  // The tracks of at least min_frames frames (where the view slid, fewer: half the frames a
  // point stays in view, at least 3; see RefineStats), numbered 0.. in order of first frame (then
  // of seed); the tracker is empty afterwards.
  std::vector<Track> finish(RefineStats* stats = nullptr);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tactile::capture
