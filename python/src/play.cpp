// play(movie, backend=...): where `tactile play` sends a movie, a Latero included, by the same
// function (display::play_anywhere), its messages written to Python's sys.stdout.

#include <fmt/format.h>

#include <fcntl.h>
#include <unistd.h>

#include <optional>

#include "bindings.hpp"
#include "tactile/display/play_anywhere.hpp"
#include "tactile/display/usb_transports.hpp"

namespace tactile::python {

namespace {

const char* target_name(display::PlaybackTarget t) {
  switch (t) {
    case display::PlaybackTarget::device:
      return "device";
    case display::PlaybackTarget::window:
      return "window";
    case display::PlaybackTarget::latero:
      return "latero";
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

// The blade mapping's keywords: unset keeps the default (OpenLatero's), as the command line's.
struct BladeArguments {
  std::optional<double> centre_raw, raw_per_unit, max_raw, full_scale_um;
  bool any() const { return centre_raw || raw_per_unit || max_raw || full_scale_um; }
};

py::dict play(const movie::TactileMovie& movie, const std::string& backend,
              std::optional<std::filesystem::path> preview, int loops,
              std::optional<std::string> address, const BladeArguments& blade) {
  if (backend != "auto" && backend != "headless" && backend != "latero") {
    throw std::invalid_argument(fmt::format(
        "backend: '{}' is not auto, headless or latero (auto: a display if one is attached, "
        "else headless; latero: the Latero at address)",
        backend));
  }
  const bool latero = backend == "latero";
  if (latero && !address) {
    throw std::invalid_argument(
        "address: backend 'latero' needs the Latero's address, HOST[:PORT] (port 8900 by "
        "default)");
  }
  if (!latero && address) {
    throw std::invalid_argument(
        fmt::format("address: only with backend 'latero' (backend is '{}')", backend));
  }
  if (!latero && blade.any()) {
    throw std::invalid_argument(fmt::format(
        "blade_*: the blade mapping is only for backend 'latero' (backend is '{}')", backend));
  }
  if (loops < 1 || loops > 1000000) {
    throw std::invalid_argument(
        fmt::format("loops: {} is out of range: must be in [1, 1000000]", loops));
  }
  display::PlayRequest request;
  request.headless = backend == "headless";
  request.preview_png = preview.value_or(std::filesystem::path{});
  request.loops = loops;
  if (latero) {
    display::LateroPlayTarget target;
    target.address = *address;
    display::LateroBladeMapping& m = target.mapping;
    m.centre_raw = blade.centre_raw.value_or(m.centre_raw);
    m.raw_per_unit = blade.raw_per_unit.value_or(m.raw_per_unit);
    m.max_raw = blade.max_raw.value_or(m.max_raw);
    m.full_scale_um = blade.full_scale_um.value_or(m.full_scale_um);
    request.latero = target;
  }
  display::PlayResult r;
  {
    const StopPipe stop;
    request.stop_fd = stop.fd();
    py::gil_scoped_release unlocked;
    // Displays on USB but no emulator window: the module links no GUI library (a window that
    // blocks the interpreter until closed is `tactile play`'s and `tactile view`'s).
    r = display::play_anywhere(
        movie, request,
        [](const std::string& text) {
          py::gil_scoped_acquire locked;
          py::module_::import("sys").attr("stdout").attr("write")(text);
        },
        display::usb_play_backends());
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
    out["movie_frames"] = p.movie_frames;
    out["ramp_frames"] = p.ramp_frames;
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
  if (r.latero_address) out["address"] = r.latero_address->text();
  if (r.latero_link) {
    const auto& l = *r.latero_link;
    const auto timing = display::summarize_timing(l, movie.rate_hz);
    out["requests_sent"] = l.requests_sent;
    out["replies_received"] = l.replies_received;
    out["missed_replies"] = l.missed_replies;
    out["late_replies"] = l.late_replies;
    out["malformed_replies"] = l.malformed_replies;
    out["achieved_rate_hz"] = timing.achieved_rate_hz;
    out["send_offset_p99_us"] = timing.offset_p99_us;
  }
  return out;
}

}  // namespace

void bind_play(py::module_& m) {
  m.def(
      "play",
      [](const movie::TactileMovie& movie, const std::string& backend,
         std::optional<std::filesystem::path> preview, int loops,
         std::optional<std::string> address, std::optional<double> blade_centre_raw,
         std::optional<double> blade_raw_per_unit, std::optional<double> blade_max_raw,
         std::optional<double> blade_full_scale_um) {
        return play(movie, backend, std::move(preview), loops, std::move(address),
                    {blade_centre_raw, blade_raw_per_unit, blade_max_raw, blade_full_scale_um});
      },
      py::arg("movie"), py::kw_only(), py::arg("backend") = "auto", py::arg("preview") = py::none(),
      py::arg("loops") = 1, py::arg("address") = py::none(),
      py::arg("blade_centre_raw") = py::none(), py::arg("blade_raw_per_unit") = py::none(),
      py::arg("blade_max_raw") = py::none(), py::arg("blade_full_scale_um") = py::none(),
      "Plays a movie as `tactile play` does, without its emulator window. backend 'auto': on\n"
      "an attached display (its vendor interface first), else headless into the emulated\n"
      "device; 'headless': the emulated device only; 'latero': the Latero at\n"
      "address HOST[:PORT] (UDP, port 8900 by default; `tactile play --latero`), a movie of the\n"
      "`latero` layout, with the blade mapping blade_centre_raw, blade_raw_per_unit,\n"
      "blade_max_raw, blade_full_scale_um (unset: OpenLatero's 75, 75, 150, 100 um). preview: a\n"
      "PNG strip of what the emulated device output (headless only). Prints what `tactile play`\n"
      "prints and returns what happened: target, the device's counters, for headless the\n"
      "largest |output| at the end (0 = at rest), for a Latero its address and the link's\n"
      "figures (requests_sent, replies_received, missed_replies, achieved_rate_hz, ...).\n"
      "Ctrl-C stops between two frames, every contactor ramped to rest, then raises\n"
      "KeyboardInterrupt.");
}

}  // namespace tactile::python
