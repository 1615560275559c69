// play(movie, backend=...): where `tactile play` sends a movie, by the same function
// (display::play_anywhere), its messages written to Python's sys.stdout.

#include <fmt/format.h>

#include <fcntl.h>
#include <unistd.h>

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

// Ctrl-C while playing: Python's own SIGINT handler writes the signal's number to the wakeup
// descriptor (signal.set_wakeup_fd), which the player watches as its stop_fd, so a stop ramps
// every contactor to rest between two frames as `tactile play` does; KeyboardInterrupt is raised
// once the player has returned. Only the main thread may set the wakeup descriptor; elsewhere
// play() runs without it.
class StopPipe {
 public:
  StopPipe() {
    int fds[2];
    if (pipe2(fds, O_CLOEXEC | O_NONBLOCK) != 0) return;
    read_ = fds[0];
    write_ = fds[1];
    try {
      old_ = py::module_::import("signal").attr("set_wakeup_fd")(write_);
    } catch (py::error_already_set&) {  // not the main thread
      close_all();
    }
  }
  ~StopPipe() {
    if (old_) {
      try {
        py::module_::import("signal").attr("set_wakeup_fd")(old_);
      } catch (py::error_already_set&) {
      }
    }
    close_all();
  }
  StopPipe(const StopPipe&) = delete;
  StopPipe& operator=(const StopPipe&) = delete;
  int fd() const { return read_; }

 private:
  void close_all() {
    if (read_ >= 0) close(read_);
    if (write_ >= 0) close(write_);
    read_ = write_ = -1;
  }
  int read_ = -1, write_ = -1;
  py::object old_;
};

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
    const StopPipe stop;
    request.stop_fd = stop.fd();
    py::gil_scoped_release unlocked;
    r = display::play_anywhere(movie, request, [](const std::string& text) {
      py::gil_scoped_acquire locked;
      py::module_::import("sys").attr("stdout").attr("write")(text);
    });
  }
  // A Ctrl-C that stopped the player is Python's KeyboardInterrupt now.
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
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
