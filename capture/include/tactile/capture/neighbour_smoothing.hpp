#pragma once
// Smoothing of each frame's steps across the skin, for a consumer that may not wait for later
// frames (a live session). Along time the smoothing can only look back there, and a window long
// enough to average the trackers' noise lags a strain that changes within a few frames
// (causal_smoothing.hpp). The skin's motion is smooth across the skin too, and a track's
// neighbours have moved in the same frame: a local quadratic of the neighbours' steps, read at
// the track, averages their independent noise with no lag and, being quadratic, keeps a strain
// that varies linearly across the neighbourhood. How far to reach depends on the strain (a
// wave of a few millimetres wants a fraction of a millimetre, a gentle field more), so the reach
// is chosen by the steps themselves: the one whose fits, each made without its own track,
// predict the tracks' measured steps best (leave-one-out), which, were the trackers' noise
// independent from track to track, would be the one closest to the skin's true motion. Tracks a
// few tenths of a millimetre apart share most of their alignment windows and so their errors,
// and with them in the fit the choice took the smallest reach every time (their errors
// predicted the track's own): the choice's fits leave out every track within
// kChoiceExcludeMm.

#include <array>
#include <vector>

#include "tactile/capture/track.hpp"

namespace tactile::capture {

struct NeighbourSmoothing {
  // Gaussian weight of a neighbour by its distance: 0 for none, 0.1 to 5 mm fixed, or
  // kChosenSigma. Neighbours beyond 2.5 sigma are left out.
  double sigma_mm = kChosenSigma;
  // Fewest steps (the track's own included) within 2.5 sigma for a fit; with fewer, or with
  // them along a line, the track keeps its own step.
  int min_neighbours = 12;
  // With a chosen sigma: chosen first after kFirstChoiceFrames frames, then every this many.
  int choose_every_frames = 30;

  static constexpr double kChosenSigma = -1;
  static constexpr int kFirstChoiceFrames = 5;
  // Tracks a frame whose leave-one-out fits go into the choice (spread over the frame).
  static constexpr int kChoiceSampleTracks = 25;
  // The choice's fits leave out the tracks this close to the one predicted (and it), and are
  // made from min_neighbours or more of the rest.
  static constexpr double kChoiceExcludeMm = 0.3;
};

// The sigmas the choice tries (mm): from about the spacing of pores (below it a fit has too
// few neighbours, and the choice's fits too few beyond kChoiceExcludeMm) to the alignment
// window's side.
inline constexpr std::array<double, 5> kNeighbourSigmaCandidatesMm = {0.3, 0.4, 0.5, 0.65, 0.8};

// Checks the ranges (sigma kChosenSigma, 0 or 0.1 to 5 mm; 6 to 1000 neighbours; a choice every
// 1 to 10000 frames); throws std::invalid_argument naming the field.
void check_neighbour_smoothing(const NeighbourSmoothing& s);

// Replaces each step's displacement (a track of two frames, as AlignmentTracker::last_step gives
// it) by the Gaussian-weighted least-squares quadratic of the displacements of the steps within
// 2.5 sigma of its first position, read there; its first position stays. sigma_mm 0: none.
void smooth_steps_across_neighbours(std::vector<Track>& steps, double px_per_mm, double sigma_mm,
                                    int min_neighbours);

// The smoothing frame after frame, its sigma fixed or chosen (see the top of this file).
class NeighbourStepSmoother {
 public:
  NeighbourStepSmoother(const NeighbourSmoothing& smoothing, double px_per_mm);

  // Adds the frame's steps to the evidence for the next choice (before smoothing: the measured
  // steps), chooses when one is due, and smooths them with the sigma in use.
  void smooth(std::vector<Track>& steps);

  double sigma_mm() const { return sigma_mm_; }  // in use (0: none, or none chosen yet)
  int choices() const { return choices_; }
  double min_chosen_mm() const { return min_chosen_mm_; }
  double max_chosen_mm() const { return max_chosen_mm_; }

 private:
  NeighbourSmoothing smoothing_;
  double px_per_mm_;
  double sigma_mm_ = 0;
  int frames_ = 0, frames_since_choice_ = 0, choices_ = 0;
  double min_chosen_mm_ = 0, max_chosen_mm_ = 0;
  std::array<double, kNeighbourSigmaCandidatesMm.size()> squared_residuals_{};
  long residuals_ = 0;
};

}  // namespace tactile::capture
