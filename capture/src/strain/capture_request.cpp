// The capture request's option table and its rules; see capture_request.hpp.

#include "tactile/capture/capture_request.hpp"

#include <fmt/format.h>

#include "tactile/capture/calibration_io.hpp"
#include "tactile/capture/pore_model_io.hpp"
#include "tactile/capture/video.hpp"

namespace tactile::capture {

namespace rows = option_rows;

const std::vector<OptionRow<CaptureRequest>>& capture_options() {
  using R = CaptureRequest;
  static const std::vector<OptionRow<R>> table = {
      rows::positional_path<R>("source", &R::source, "IMAGE_DIR",
                               "Folder of frames (image files in name order), or a video file "
                               "(.mp4 .avi .mkv .mov)"),
      rows::existing_path<R>("calib", &R::calib, "Calibration JSON from `tactile calibrate`"),
      rows::number<R>("px_per_mm", &R::px_per_mm, kMinPxPerMm, kMaxPxPerMm, "px/mm",
                      "Uniform scale instead of a calibration file"),
      rows::number<R>("start", &R::start, 0, 1e8, "", "First frame to use (0 = the first)"),
      rows::number<R>("frames", &R::frames, 1, 1e8, "",
                      "Number of frames to use (default: all from start)"),
      rows::number<R>("rate_hz", &R::rate_hz, 1, 1e5, "Hz",
                      fmt::format("Camera frame rate (default: a video's own rate from its "
                                  "container, else {} Hz)",
                                  kCameraRateHz)),
      rows::number<R>("span", &R::span, 1, 10000, "frames",
                      "Frames between the two ends of each strain measurement"),
      rows::number<R>("min_track", &R::min_track, 2, 100000, "frames",
                      "Shortest track kept (tracks linked from detections, without refinement;\n"
                      "refined tracks are kept from 10 frames)"),
      rows::choice<R>(
          "pores", &R::pores, kPoreSettingNames,
          "Pore detector: paper (binarised blobs; fast) or ridge-blob (bright spots "
          "above\ntheir own ridge, kept by a pore model trained on hand-marked 1200 dpi "
          "prints;\nfinds open pores on real prints at about 47 px/mm, slower); auto: "
          "the one that\nfinds more pores on the first frame (printed)"),
      rows::existing_path<R>("pore_model", &R::pore_model,
                             "Pore model file from `tactile train-pores` (with pores ridge-blob), "
                             "used\nwith its threshold instead of the shipped model"),
      rows::choice<R>("refine", &R::refine, kRefineSettingNames,
                      "Sub-pixel refinement of every track against the images (each landmark's\n"
                      "neighbourhood aligned to its first frame by an affine warp): auto = with "
                      "the\nridge-blob detector, whose centres on real prints are noisy"),
      rows::number<R>("refine_window", &R::refine_window_mm, 0.1, 5.0, "mm",
                      "Side of the refinement's alignment window (smaller follows strain\n"
                      "gradients better, larger averages more noise)"),
      rows::number<R>(
          "smoothing", &R::smoothing, 0, 50, "frames",
          fmt::format("Half-window of the trajectory smoothing (local quadratic over "
                      "2 H + 1 frames;\n0 = none); default {}; with refinement the "
                      "longest tried (default {}, weights\nfalling towards the window's "
                      "ends): the capture takes whichever of H, 14, 12, 10,\n8, 7, 6, 5, "
                      "4, 3 or none leaves the least error it estimates from the "
                      "changes\nbetween neighbouring tracks",
                      smoothing_half_window_for(false), smoothing_half_window_for(true))),
      rows::choice<R>("assignment", &R::assignment, kAssignmentNames,
                      "Frame-to-frame matching: greedy by confidence, or optimal (maximum total "
                      "confidence,\nHungarian method)"),
  };
  return table;
}

void check_one_scale(bool calib_given, bool px_per_mm_given, OptionSpelling spelling) {
  if (calib_given == px_per_mm_given) {
    throw RequestError(fmt::format("give one of {} (a calibration file) or {}",
                                   option_label("calib", spelling),
                                   option_label("px_per_mm", spelling)));
  }
}

void check_request(const CaptureRequest& request, OptionSpelling spelling) {
  const auto label = [spelling](std::string_view name) { return option_label(name, spelling); };
  check_one_scale(request.calib.has_value(), request.px_per_mm.has_value(), spelling);
  // Every value again, for a request filled in without set_option (a program's own struct).
  check_options(request, capture_options(), spelling);
  if (request.pore_model && request.pores == PoreSetting::paper) {
    throw RequestError(fmt::format("{}: goes with {} ridge-blob (the paper's rule has no model)",
                                   label("pore_model"), label("pores")));
  }
}

ResolvedCapture resolve(const CaptureRequest& request, OptionSpelling spelling) {
  check_request(request, spelling);
  // A single image (or any file that is not a video) where a folder of frames is expected is
  // the wrong kind of input, as a value out of range is: the caller's to correct.
  std::error_code ec;
  if (std::filesystem::is_regular_file(request.source, ec) && !is_video_name(request.source)) {
    throw RequestError(fmt::format(
        "{}: {} is a single file, not a folder of frames or a video (give the folder that "
        "holds the frames)",
        spelling == OptionSpelling::cli ? "IMAGE_DIR" : "source", request.source.string()));
  }
  ResolvedCapture r;
  r.frames = std::make_unique<FrameRange>(request.source, request.start, request.frames);
  if (const std::string range = r.frames->range_error(spelling); !range.empty()) {
    throw RequestError(range);
  }
  if (request.calib) r.calibration = read_calibration_json(*request.calib);
  r.px_per_mm = request.px_per_mm;
  if (request.rate_hz) {
    r.rate_hz = *request.rate_hz;
    r.rate_from = "given";
  } else if (r.frames->is_video()) {
    r.rate_hz = r.frames->frame_rate_hz();
    r.rate_from = "the video's container";
  } else {
    r.rate_hz = kCameraRateHz;
    r.rate_from = "the default for a folder of frames";
  }
  CaptureSettings& s = r.settings;
  s.pores = request.pores;
  s.refine = request.refine;
  s.smoothing_half_window = request.smoothing;
  s.refine_window_mm = request.refine_window_mm;
  s.span_frames = request.span;
  s.min_track_frames = request.min_track;
  s.assignment = request.assignment;
  if (request.pore_model) s.pore_model = read_pore_model_json(*request.pore_model);
  if (request.calib) s.calibration_source = request.calib->string();
  return r;
}

}  // namespace tactile::capture
