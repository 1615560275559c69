#pragma once
// `live` as a request: a camera (or a stream, or a file played as a camera would deliver it)
// through capture, strain and mapping to a display, frame by frame. Its options are the capture
// and map requests' own rows (scale, detector, layout, method, gain: their help, ranges and
// defaults written once there) and a few of its own.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tactile/capture/capture.hpp"
#include "tactile/capture/capture_request.hpp"
#include "tactile/capture/causal_smoothing.hpp"
#include "tactile/capture/neighbour_smoothing.hpp"
#include "tactile/common/option_table.hpp"
#include "tactile/mapping/map_request.hpp"

namespace tactile::live {

struct LiveRequest {
  // A V4L2 camera (/dev/videoN), a stream (udp://, tcp://, rtsp://), or a video file or folder
  // of frames played at its frame rate as a camera would deliver it.
  std::string source;
  capture::CaptureRequest capture;  // calib or px_per_mm, rate_hz, pores, refine_window
  mapping::MapRequest map;          // layout, method, gain
  std::optional<double> seconds;    // unset: until the source ends or a stop
  std::optional<std::filesystem::path> record;
  // Unset: queue_frames_for(the camera's rate).
  std::optional<int> queue_frames;
  // Frames between detections of new landmarks: the batch capture's own rhythm.
  int detect_every = capture::CaptureParams{}.redetect_every_frames;
  // Positions of each track fitted by the causal smoothing (0: none); unset: chosen by the tracks.
  std::optional<int> smooth_frames;
  // Gaussian reach of the smoothing of each frame's steps across neighbouring tracks (mm; 0:
  // none); unset: chosen by the steps.
  std::optional<double> neighbour_sigma_mm;
  // Least distance between tracked landmarks (mm; 0: every landmark found); unset: as the
  // session's time needs (see ResolvedLive).
  std::optional<double> min_spacing_mm;
};

const std::vector<OptionRow<LiveRequest>>& live_options();

// The frames a queue holds when none is asked for: kQueueSeconds of the camera's frames, at
// least 4, at most 64. Room for the first frame's extra work (choosing the pore detector and
// detecting in line: the largest latency of 320 x 240 sessions on the 2-core machine here was
// 42-45 ms, 3 frames at 60 Hz and 5 at 120 Hz) without a drop; in steady state the queue is
// empty and adds no latency.
inline constexpr double kQueueSeconds = 0.05;
int queue_frames_for(double camera_rate_hz);

// Whether `source` names a file or folder (played at its rate) rather than a device or stream.
bool is_rehearsal_source(const std::string& source);

struct ResolvedLive {
  std::string source;
  bool rehearsal = false;
  std::optional<capture::Calibration> calibration;  // from calib; unset: uniform px_per_mm
  std::optional<double> px_per_mm;
  std::optional<double> rate_hz;  // a camera rate asked for (else the source's own)
  capture::PoreSetting pores = capture::PoreSetting::automatic;
  double refine_window_mm = 0;
  movie::Layout layout;
  mapping::MappingParams params;  // resolved: rate_hz is the device's
  std::optional<double> seconds;
  std::optional<std::filesystem::path> record;
  std::optional<int> queue_frames;  // unset: queue_frames_for(the camera's rate)
  int detect_every = 0;
  capture::CausalSmoothing smoothing;
  capture::NeighbourSmoothing neighbour_smoothing;
  // Unset: every landmark found while the session keeps up, and landmarks spaced further apart
  // when a frame's tracking, strain and mapping take more than kBusyShare of the camera's period
  // (closer again below kIdleShare), judged on kFirstDensityFrames frames after kWarmUpFrames,
  // then every kDensityFrames.
  std::optional<double> min_spacing_mm;
};

inline constexpr double kBusyShare = 0.6;
inline constexpr double kIdleShare = 0.45;
inline constexpr int kDensityFrames = 30;
inline constexpr int kFirstDensityFrames = 10;
// Frames not judged at the start: the first frames' references and the detector's choice make
// them slower than any that follow.
inline constexpr int kWarmUpFrames = 10;
// The sparsest the session spaces landmarks on its own. Further apart the live strain's error
// rises well past the batch capture's (0.4 mm: 1.28 times it at 640 x 484, about 400 landmarks
// a frame), and the work that does not depend on the tracks is not saved: a session still
// behind there drops frames instead (an emulated CPU in the vm tests, 166 ms a frame, spaced
// them to 0.71 mm and 62 points a frame before this bound).
inline constexpr double kMaxSpacingMm = 0.4;

// Checks every value and the rules between them (RequestError in the front end's spelling): one
// of calib and px_per_mm; a mapping that needs no later frame (normalisation none, strain per
// frame, not the profile method); the record folder new or empty.
ResolvedLive resolve(const LiveRequest& request, OptionSpelling spelling);

// A Latero plays the latero layout only (a movie of another lands on the wrong blades):
// RequestError naming the layout option, before anything is sent to it.
void require_latero_layout(const ResolvedLive& session, OptionSpelling spelling);

}  // namespace tactile::live
