// play(movie, backend=...): where `tactile play` sends a movie, by the same function
// (display::play_anywhere), its messages written to Python's sys.stdout.

#include <fmt/format.h>

#include <optional>

#include "bindings.hpp"
#include "tactile/display/play_anywhere.hpp"

namespace tactile::python {

namespace {

const char* target_name(display::PlaybackTarget t) {
  switch (t) {
    case display::PlaybackTarget::device:
      return "device";
    case display::PlaybackTarget::window:
      return "window";
    case display::PlaybackTarget::headless:
      break;
  }
  return "headless";
}

py::dict play(const movie::TactileMovie& movie, const std::string& backend,
              std::optional<std::filesystem::path> preview, int loops) {
  if (backend != "auto" && backend != "headless") {
    throw std::invalid_argument(fmt::format(
        "backend: '{}' is not auto or headless (auto: a display if one is attached, else the "
        "emulator window if there is a screen, else headless)",
        backend));
  }
  if (loops < 1 || loops > 1000000) {
    throw std::invalid_argument(
        fmt::format("loops: {} is out of range: must be in [1, 1000000]", loops));
  }
  display::PlayRequest request;
  request.headless = backend == "headless";
  request.preview_png = preview.value_or(std::filesystem::path{});
  request.loops = loops;
  display::PlayResult r;
  {
    py::gil_scoped_release unlocked;
    r = display::play_anywhere(movie, request, [](const std::string& text) {
      py::gil_scoped_acquire locked;
      py::module_::import("sys").attr("stdout").attr("write")(text);
    });
  }
  py::dict out;
  out["target"] = target_name(r.target);
  out["stopped"] = r.stopped;
  out["preview"] = r.preview_png ? py::cast(*r.preview_png) : py::none();
  out["device"] = r.device ? py::cast(r.device->path) : py::none();
  if (r.report) {
    const auto& p = *r.report;
    out["frames_played"] = p.frames_played;
    out["frames_sent"] = p.frames_sent;
    out["rate_hz"] = p.rate_hz;
    out["duration_s"] = p.duration_s;
    out["underruns"] = p.underruns;
    out["malformed"] = p.malformed;
    out["clamped_samples"] = p.clamped_samples;
    out["slew_limited_samples"] = p.slew_limited_samples;
  }
  if (r.target == display::PlaybackTarget::headless) out["final_max_um"] = r.final_max_um;
  return out;
}

}  // namespace

void bind_play(py::module_& m) {
  m.def("play", &play, py::arg("movie"), py::kw_only(), py::arg("backend") = "auto",
        py::arg("preview") = py::none(), py::arg("loops") = 1,
        "Plays a movie as `tactile play` does. backend 'auto': on an attached display (its\n"
        "vendor interface first), else the emulator window if there is a screen, else headless\n"
        "into the emulated device; 'headless': the emulated device only. preview: a PNG strip of\n"
        "what the emulated device output (headless only). Prints what `tactile play` prints and\n"
        "returns what happened: target, the device's counters, and for headless the largest\n"
        "|output| at the end (0 = at rest).");
}

}  // namespace tactile::python
