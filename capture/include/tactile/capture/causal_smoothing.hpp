#pragma once
// Smoothing of tracks as the frames come, for a consumer that may not wait for later frames (a
// live session). The batch capture smooths each track with a local quadratic fit centred on the
// frame (smooth_tracks); here the fit can only look back, so it is a polynomial fitted to the
// track's last positions and read at the step's two frames. Looking back costs no latency but
// lags a strain that changes quickly: a longer window averages more of the trackers' noise and
// follows fast changes less well. So, as the batch capture's smoothing, the window is chosen
// by the tracks themselves (causal_smoothing_that_fits), again and again as the session goes:
// a camera at 240 Hz sees the same strain change over four times the frames it does at 60 Hz.

#include <cstdint>
#include <map>
#include <vector>

#include "tactile/capture/track.hpp"

namespace tactile::capture {

struct CausalSmoothing {
  // Positions fitted, the step's two included: 0 for none, 4..30, or kChosenWindow.
  int window_frames = kChosenWindow;
  int degree = 2;  // of the polynomial in time, 1 or 2
  // With a chosen window: chosen this often (frames) from the tracks' last kHistoryFrames
  // frames, none until kCausalChoiceFrames frames have come.
  int choose_every_frames = 30;

  static constexpr int kChosenWindow = -1;
  static constexpr int kHistoryFrames = 60;
};

// The weights on positions measured at `times_frames` that give the least-squares polynomial of
// `degree` through them, read at `read_at_frames`.
std::vector<double> polynomial_fit_weights(const std::vector<double>& times_frames, int degree,
                                           double read_at_frames);

// Checks the ranges (window kChosenWindow, 0 or 4..30 frames; degree 1 or 2; choice every 1 to
// 10000 frames); throws std::invalid_argument naming the field.
void check_causal_smoothing(const CausalSmoothing& s);

class CausalTrackSmoother {
 public:
  explicit CausalTrackSmoother(const CausalSmoothing& smoothing);

  // Replaces the two positions of each step (a track of two frames, as AlignmentTracker::
  // last_step gives it, followed from camera frame `frame_from` into `frame_to`) by the fit over
  // the track's positions up to `frame_to`. A track seen in fewer frames than the fit needs
  // (degree + 2) keeps its measured step. Tracks absent from `steps` are forgotten.
  void smooth(std::int64_t frame_from, std::int64_t frame_to, std::vector<Track>& steps);

  // With a chosen window: whether the steps seen call for a choice now (kCausalChoiceFrames
  // steps, then every choose_every_frames), and what to choose by: each track's last run of
  // consecutive camera frames in the history (a dropped frame breaks the equal spacing the
  // choice assumes), as tracks on the camera's frame numbers. The choice itself
  // (causal_smoothing_that_fits) is the caller's to run, in line or on a thread of its own.
  bool choice_due() const;
  std::vector<Track> tracks_to_choose_by() const;
  void set_window(int window_frames);  // 0 or 4..30 (what the choice gives)

  // The window in use (0: none yet, or none chosen).
  int window_frames() const { return window_frames_; }

 private:
  struct Position {
    std::int64_t frame;
    double x_px, y_px;
  };

  CausalSmoothing smoothing_;
  int window_frames_ = 0;
  // The fit's weights at the step's two frames by the positions' frames (from the step's last):
  // one entry while no frame is dropped.
  std::map<std::vector<std::int64_t>, std::pair<std::vector<double>, std::vector<double>>> weights_;
  std::int64_t steps_seen_ = 0;
  std::map<std::int32_t, std::vector<Position>> history_;
};

}  // namespace tactile::capture
