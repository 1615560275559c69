#pragma once
// Generic optical-flow trackers, run in the same harness as the landmark pipeline so that their
// strain (same Delaunay computation, strain_from_tracks) can be compared with it: OpenCV's
// pyramidal Lucas-Kanade on corner features, and DIS dense optical flow sampled on a grid.

#include <vector>

#include "tactile/capture/image.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/capture/track.hpp"

namespace tactile::capture {

struct LucasKanadeParams {
  int max_corners = 800;          // goodFeaturesToTrack
  double corner_quality = 0.01;   // relative to the strongest corner
  double min_distance_mm = 0.25;  // between corners (about one pore spacing / 2)
  int window_px = 15;             // LK integration window
  int pyramid_levels = 3;
  double max_forward_backward_px = 0.5;    // a point must track back to where it started
  int reseed_every_frames = 5;             // new corners where the tracked ones thinned out
  int min_track_frames = kMinTrackFrames;  // as the landmark pipeline
};

struct DisFlowParams {
  double grid_spacing_mm = 0.3;   // seed points on a square grid ...
  double min_texture_std = 12.0;  // ... where the print has contrast (grey levels, 0.3 mm window)
  int preset = 1;                 // cv::DISOpticalFlow preset: 0 ultrafast, 1 fast, 2 medium
  int reseed_every_frames = 5;
  int min_track_frames = kMinTrackFrames;
};

// Tracks numbered 0.. in order of first frame, positions in pixels, type `pore` (a point of
// skin). Frames must all have one size (std::invalid_argument otherwise); no frames, no tracks.
std::vector<Track> track_lucas_kanade(const std::vector<GrayImage>& frames,
                                      const Calibration& calibration,
                                      const LucasKanadeParams& params = {});
std::vector<Track> track_dis_flow(const std::vector<GrayImage>& frames,
                                  const Calibration& calibration, const DisFlowParams& params = {});

}  // namespace tactile::capture
