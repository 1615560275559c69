#pragma once
// `capture` as a request: what a person asks of a capture run (the source, the scale, the
// settings), its option table (read by the command line and the Python module alike) and
// resolve(), which holds the rules between the options and those that need the input (a video's
// own frame rate, the range of frames it has). Every default of a capture is the member
// initialiser below and nowhere else.

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tactile/capture/calibrate.hpp"
#include "tactile/capture/capture_run.hpp"
#include "tactile/common/option_table.hpp"

namespace tactile::capture {

// Pixels per millimetre a fingertip camera can have: a 5-50 mm field on 100-10000 px spans
// 2-2000 px/mm; the upper bound leaves room for microscope-like optics.
inline constexpr double kMinPxPerMm = 2.0;
inline constexpr double kMaxPxPerMm = 5000.0;

struct CaptureRequest {
  std::filesystem::path source;  // a folder of frames or a video file
  std::optional<std::filesystem::path> calib;
  std::optional<double> px_per_mm;
  int start = 0;
  std::optional<int> frames;      // unset: every frame from start on
  std::optional<double> rate_hz;  // unset: a video's own rate, else kCameraRateHz
  int span = 1;
  int min_track = kMinTrackFrames;
  PoreSetting pores = PoreSetting::automatic;
  std::optional<std::filesystem::path> pore_model;
  RefineSetting refine = RefineSetting::automatic;
  double refine_window_mm = RefineParams{}.window_mm;
  std::optional<int> smoothing;  // unset: chosen by the capture (see the option's help)
  Assignment assignment = Assignment::greedy;
};

const std::vector<OptionRow<CaptureRequest>>& capture_options();

// Exactly one of a calibration file and a uniform scale (RequestError otherwise): the rule of
// every request that measures from images.
void check_one_scale(bool calib_given, bool px_per_mm_given, OptionSpelling spelling);

// The rules between the options that need no file: exactly one of calib and px_per_mm; a pore
// model only with a detector that uses one. Throws RequestError in the front end's spelling.
void check_request(const CaptureRequest& request, OptionSpelling spelling);

// A request made ready to run: the frames opened, the files it names read, the rate decided.
struct ResolvedCapture {
  std::unique_ptr<FrameRange> frames;
  std::optional<Calibration> calibration;  // from calib; unset: uniform px_per_mm
  std::optional<double> px_per_mm;
  double rate_hz = kCameraRateHz;
  std::string rate_from;  // where rate_hz came from, for a person: "given", "the video", ...
  CaptureSettings settings;
};

// check_request, then opens the source and checks the range of frames against it (RequestError),
// reads the calibration and the pore model (FormatError naming the file) and decides the rate.
ResolvedCapture resolve(const CaptureRequest& request, OptionSpelling spelling);

}  // namespace tactile::capture
