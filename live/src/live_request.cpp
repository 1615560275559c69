// The live request's option table and its rules; see live_request.hpp.

#include "tactile/live/live_request.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "tactile/capture/calibration_io.hpp"
#include "tactile/capture/video.hpp"

namespace tactile::live {

namespace rows = option_rows;
namespace fs = std::filesystem;

const std::vector<OptionRow<LiveRequest>>& live_options() {
  using R = LiveRequest;
  static const std::vector<OptionRow<R>> table = [] {
    std::vector<OptionRow<R>> t;
    OptionRow<R> source = rows::path<R>(
        "source", &R::source,
        "A V4L2 camera (/dev/videoN), a stream (udp://, tcp://, rtsp://), or a video file or\n"
        "folder of frames played at its frame rate as a camera would deliver it");
    source.positional = true;
    source.metavar = "SOURCE";
    t.push_back(source);
    rows::append_nested<R>(t, capture::capture_options(),
                           [](auto& r) -> auto& { return r.capture; },
                           {"calib", "px_per_mm", "rate_hz", "pores", "refine_window"});
    rows::append_nested<R>(t, mapping::map_options(), [](auto& r) -> auto& { return r.map; },
                           {"layout", "method", "gain"});
    t.push_back(rows::number<R>("seconds", &R::seconds, 0.01, 1e6, "s",
                                "Stop after this long (default: when the source ends, or Ctrl-C)"));
    t.push_back(rows::path<R>(
        "record", &R::record,
        "Record the session into this new (or empty) folder as it goes (frames.mkv,\n"
        "latency.csv, tracks.csv, edges.csv, strain.h5, movie.h5), on the disk every half "
        "second"));
    t.push_back(rows::number<R>("queue_frames", &R::queue_frames, 1, 64, "frames",
                                "Frames waiting between the camera and the processing; when "
                                "full, the oldest\nis dropped (and counted) (default: 50 ms of "
                                "the camera's frames, at least 4)"));
    t.push_back(rows::number<R>("detect_every", &R::detect_every, 1, 1000, "frames",
                                "Frames between detections of new landmarks (between them, "
                                "landmarks are\nfollowed by alignment alone; sooner when a "
                                "fifth of the tracks ended)"));
    t.push_back(rows::number<R>(
        "smooth_frames", &R::smooth_frames, 0, 30, "frames",
        "Positions of each track fitted (a quadratic, looking back only) to smooth its step\n"
        "into each frame: 0 for none, else 4 to 30 (default: chosen by the tracks' own noise\n"
        "every 30 frames, as the batch capture chooses its smoothing)"));
    t.push_back(rows::number<R>(
        "neighbour_sigma", &R::neighbour_sigma_mm, 0, 5, "mm",
        "Reach (Gaussian sigma) of the smoothing of each frame's steps across neighbouring\n"
        "tracks, a local quadratic read at each track (no look-ahead): 0 for none, else 0.1\n"
        "to 5 (default: chosen by the steps, the reach whose fits best predict tracks left out)"));
    t.push_back(rows::number<R>(
        "min_spacing", &R::min_spacing_mm, 0, 5, "mm",
        "Least distance between tracked landmarks: 0 for every landmark found (default: every\n"
        "one while the session keeps up with the camera; spaced further apart when a frame's\n"
        "tracking, strain and mapping take over 60 % of the camera's period, up to 0.4, e.g.\n"
        "640 x 484 at 60 Hz on two cores)"));
    return t;
  }();
  return table;
}

bool is_rehearsal_source(const std::string& source) {
  if (source.find("://") != std::string::npos) return false;
  if (source.rfind("/dev/", 0) == 0) return false;
  return true;
}

ResolvedLive resolve(const LiveRequest& request, OptionSpelling spelling) {
  check_options(request, live_options(), spelling);
  const auto label = [spelling](std::string_view name) { return option_label(name, spelling); };
  const capture::CaptureRequest& c = request.capture;
  capture::check_one_scale(c.calib.has_value(), c.px_per_mm.has_value(), spelling);
  ResolvedLive r;
  r.source = request.source;
  r.rehearsal = is_rehearsal_source(request.source);
  std::error_code ec;
  if (r.rehearsal && !fs::exists(request.source, ec)) {
    throw RequestError(fmt::format("{}: no such file or folder: {}",
                                   spelling == OptionSpelling::cli ? "SOURCE" : "source",
                                   request.source));
  }
  // A single image where a camera, a stream, a video or a folder of frames is expected is the
  // wrong kind of input (as `capture` says for it): the caller's to correct.
  if (r.rehearsal && fs::is_regular_file(request.source, ec) &&
      !capture::is_video_name(request.source)) {
    throw RequestError(fmt::format(
        "{}: {} is a single file, not a camera, a stream, a video or a folder of frames",
        spelling == OptionSpelling::cli ? "SOURCE" : "source", request.source));
  }
  const mapping::MappingParams& p = request.map.params;
  // The session maps each frame when it arrives: a rule that needs the whole movie cannot apply.
  if (p.normalisation != mapping::Normalisation::none) {
    throw RequestError(
        "a live session maps each frame as it arrives: normalisation needs the "
        "whole movie (use gain)");
  }
  if (p.method == mapping::MappingMethod::profile) {
    throw RequestError(
        fmt::format("{}: profile needs a surface profile, which a camera does not "
                    "give",
                    label("method")));
  }
  if (request.record) {
    const fs::path& dir = *request.record;
    if (fs::exists(dir, ec) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec))) {
      throw RequestError(
          fmt::format("{}: {} exists and is not an empty folder: a recording goes "
                      "into a new one, so that nothing is written over",
                      label("record"), dir.string()));
    }
  }
  if (c.calib) r.calibration = capture::read_calibration_json(*c.calib);
  r.px_per_mm = c.px_per_mm;
  r.rate_hz = c.rate_hz;
  r.pores = c.pores;
  r.refine_window_mm = c.refine_window_mm;
  const mapping::ResolvedMap m = mapping::resolve(request.map, spelling);
  r.layout = m.layout;
  r.params = m.params;
  r.seconds = request.seconds;
  r.record = request.record;
  r.queue_frames = request.queue_frames;
  r.detect_every = request.detect_every;
  if (request.smooth_frames) {
    if (*request.smooth_frames > 0 && *request.smooth_frames < 4) {
      throw RequestError(fmt::format(
          "{}: {} frames is too few for a quadratic fit with a frame to spare: give 0 (none) or "
          "4 to 30",
          label("smooth_frames"), *request.smooth_frames));
    }
    r.smoothing.window_frames = *request.smooth_frames;
  }
  if (request.neighbour_sigma_mm) {
    if (*request.neighbour_sigma_mm > 0 && *request.neighbour_sigma_mm < 0.1) {
      throw RequestError(fmt::format(
          "{}: {:g} mm reaches fewer tracks than a quadratic fit needs: give 0 (none) or 0.1 to "
          "5 mm",
          label("neighbour_sigma"), *request.neighbour_sigma_mm));
    }
    r.neighbour_smoothing.sigma_mm = *request.neighbour_sigma_mm;
  }
  r.min_spacing_mm = request.min_spacing_mm;
  return r;
}

int queue_frames_for(double camera_rate_hz) {
  if (!(camera_rate_hz > 0) || !std::isfinite(camera_rate_hz)) return 4;
  return static_cast<int>(std::clamp(std::ceil(camera_rate_hz * kQueueSeconds), 4.0, 64.0));
}

void require_latero_layout(const ResolvedLive& session, OptionSpelling spelling) {
  if (session.layout.name != "latero") {
    throw RequestError(
        fmt::format("{}: a Latero plays the latero layout (8 x 8 blades); give "
                    "latero, not {}",
                    option_label("layout", spelling), session.layout.name));
  }
}

}  // namespace tactile::live
