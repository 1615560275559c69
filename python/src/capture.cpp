// capture(source, ...): a strain movie from a folder of frames or a video, by the run
// `tactile capture` makes (capture::capture_strain), with its options and defaults.

#include <fmt/format.h>

#include <memory>
#include <optional>

#include "bindings.hpp"
#include "tactile/capture/calibration_io.hpp"
#include "tactile/capture/capture_run.hpp"
#include "tactile/common/version.hpp"

namespace tactile::python {

namespace {

namespace fs = std::filesystem;

std::shared_ptr<capture::StrainMovie> capture_movie(
    const fs::path& source, std::optional<double> px_per_mm, std::optional<fs::path> calib,
    int start, std::optional<int> frames, std::optional<double> rate_hz, int span, int min_track,
    const std::string& pores, const std::string& refine, std::optional<int> smoothing,
    const std::string& assignment, std::optional<fs::path> pore_model) {
  if (px_per_mm.has_value() == calib.has_value()) {
    throw std::invalid_argument("give one of calib (a calibration file) or px_per_mm");
  }
  if (px_per_mm && !(*px_per_mm >= 2 && *px_per_mm <= 5000)) {
    throw std::invalid_argument(
        fmt::format("px_per_mm: {:g} is out of range: must be in [2, 5000]", *px_per_mm));
  }
  if (rate_hz && !(*rate_hz >= 1 && *rate_hz <= 100000)) {
    throw std::invalid_argument(
        fmt::format("rate_hz: {:g} is out of range: must be in [1, 100000]", *rate_hz));
  }
  capture::CaptureSettings settings;
  settings.pores = parse_name("pores", pores, capture::kPoreSettingNames);
  settings.refine = parse_name("refine", refine, capture::kRefineSettingNames);
  settings.assignment = parse_name("assignment", assignment, capture::kAssignmentNames);
  if (pore_model && settings.pores == capture::PoreSetting::paper) {
    throw std::invalid_argument(
        "pore_model goes with pores='ridge-blob' (the paper's rule has no model)");
  }
  settings.smoothing_half_window = smoothing;
  settings.span_frames = span;
  settings.min_track_frames = min_track;
  if (span < 1 || min_track < 2 || (smoothing && (*smoothing < 0 || *smoothing > 50))) {
    throw std::invalid_argument(
        fmt::format("span ({}) must be >= 1, min_track ({}) >= 2, smoothing ({}) in [0, 50]", span,
                    min_track, smoothing.value_or(0)));
  }
  py::gil_scoped_release unlocked;
  return with_inputs({source, calib.value_or(fs::path{}), pore_model.value_or(fs::path{})}, [&] {
    capture::FrameRange input(source, start, frames);
    if (const std::string range = input.range_error(); !range.empty()) {
      throw std::invalid_argument(range);
    }
    const std::optional<capture::Calibration> calibration =
        calib ? std::optional(capture::read_calibration_json(*calib)) : std::nullopt;
    if (pore_model) settings.pore_model = capture::read_pore_model_json(*pore_model);
    const double rate = rate_hz.value_or(input.is_video() ? input.frame_rate_hz() : 60.0);
    const capture::CaptureMessages messages{
        .note =
            [](const std::string& text) {
              py::gil_scoped_acquire locked;
              py::module_::import("sys").attr("stdout").attr("write")("capture: " + text + "\n");
            },
        .warning =
            [](const std::string& text) {
              py::gil_scoped_acquire locked;
              PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 1);
            }};
    auto movie = std::make_shared<capture::StrainMovie>(
        capture::capture_strain(input, calibration, px_per_mm, rate, settings, messages));
    if (capture::measured_no_strain(*movie)) {
      throw std::runtime_error(capture::no_strain_reason(*movie, settings, source));
    }
    movie->provenance.input = source.string();
    return movie;
  });
}

}  // namespace

void bind_capture(py::module_& m) {
  m.def(
      "capture", &capture_movie, py::arg("source"), py::kw_only(),
      py::arg("px_per_mm") = py::none(), py::arg("calib") = py::none(), py::arg("start") = 0,
      py::arg("frames") = py::none(), py::arg("rate_hz") = py::none(), py::arg("span") = 1,
      py::arg("min_track") = 30, py::arg("pores") = "auto", py::arg("refine") = "auto",
      py::arg("smoothing") = py::none(), py::arg("assignment") = "greedy",
      py::arg("pore_model") = py::none(),
      "A strain movie from a folder of frames (image files in name order) or a video (.mp4\n"
      ".avi .mkv .mov), as `tactile capture`: calib (a file from `tactile calibrate`) or\n"
      "px_per_mm; frames start.. start+frames-1; rate_hz: the camera's (a video's own by\n"
      "default, else 60); pores auto|paper|ridge-blob and refine auto|on|off (auto prints what it\n"
      "chose); assignment greedy|optimal.");
}

}  // namespace tactile::python
