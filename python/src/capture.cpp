// capture(source, ...): a strain movie from a folder of frames or a video, by the run
// `tactile capture` makes (capture::capture_strain), its keywords made from the capture request's
// option table (capture::capture_options) and resolved by the same rules.

#include <memory>

#include "bindings.hpp"
#include "request_kwargs.hpp"
#include "tactile/capture/capture_request.hpp"

namespace tactile::python {

namespace {

namespace fs = std::filesystem;

std::shared_ptr<capture::StrainMovie> capture_movie(const fs::path& source,
                                                    const py::kwargs& kwargs) {
  capture::CaptureRequest request;
  request.source = source;
  set_from_kwargs(request, capture::capture_options(), kwargs, "capture");
  capture::check_request(request, OptionSpelling::python);
  py::gil_scoped_release unlocked;
  return with_inputs(
      {source, request.calib.value_or(fs::path{}), request.pore_model.value_or(fs::path{})}, [&] {
        capture::ResolvedCapture run = capture::resolve(request, OptionSpelling::python);
        const capture::CaptureMessages messages{
            .note = [](const std::string& text) { write_python_stdout("capture: " + text + "\n"); },
            .warning =
                [](const std::string& text) {
                  py::gil_scoped_acquire locked;
                  PyErr_WarnEx(PyExc_UserWarning, text.c_str(), 1);
                }};
        auto movie = std::make_shared<capture::StrainMovie>(capture::capture_strain(
            *run.frames, run.calibration, run.px_per_mm, run.rate_hz, run.settings, messages));
        if (capture::measured_no_strain(*movie)) {
          throw std::runtime_error(capture::no_strain_reason(*movie, run.settings, source));
        }
        movie->provenance.input = source.string();
        return movie;
      });
}

}  // namespace

void bind_capture(py::module_& m) {
  def_with_kwargs(
      m, "capture", &capture_movie, capture::capture_options(),
      "A strain movie from a folder of frames (image files in name order) or a video (.mp4\n"
      ".avi .mkv .mov), as `tactile capture`; give calib (a file from `tactile calibrate`) or\n"
      "px_per_mm. Keywords (the command line's options, with underscores):",
      py::arg("source"));
}

}  // namespace tactile::python
