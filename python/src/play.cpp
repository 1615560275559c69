// play(movie, ...): where `tactile play` sends a movie, a Latero included, by the same
// function (display::play_anywhere), its messages written to Python's sys.stdout.

#include <fmt/format.h>

#include <fcntl.h>
#include <unistd.h>

#include <optional>

#include "bindings.hpp"
#include "request_kwargs.hpp"
#include "tactile/display/play_anywhere.hpp"
#include "tactile/display/play_request.hpp"
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

py::dict play(const movie::TactileMovie& movie, const py::kwargs& kwargs) {
  display::PlayRequest request;
  set_from_kwargs(request, display::play_options(), kwargs, "play");
  display::ResolvedPlay choice = display::resolve(request, OptionSpelling::python);
  display::PlayResult r;
  {
    const StopPipe stop;
    choice.stop_fd = stop.fd();
    py::gil_scoped_release unlocked;
    // Displays on USB but no emulator window: the module links no GUI library (a window that
    // blocks the interpreter until closed is `tactile play`'s and `tactile view`'s).
    r = display::play_anywhere(movie, choice, write_python_stdout, display::usb_play_backends());
  }
  // A Ctrl-C that stopped the player is Python's KeyboardInterrupt now.
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  py::dict out;
  out["target"] = target_name(r.target);
  out["stopped"] = r.stopped;
  out["preview"] = r.preview_png ? py::cast(*r.preview_png) : py::none();
  out["device"] = r.device ? py::cast(r.device->path) : py::none();
  if (r.report) {
    using P = display::PlaybackReport;
    put_fields(out, *r.report, field("movie_frames", &P::movie_frames),
               field("ramp_frames", &P::ramp_frames), field("frames_played", &P::frames_played),
               field("frames_sent", &P::frames_sent), field("rate_hz", &P::rate_hz),
               field("duration_s", &P::duration_s), field("underruns", &P::underruns),
               field("malformed", &P::malformed), field("clamped_samples", &P::clamped_samples),
               field("slew_limited_samples", &P::slew_limited_samples));
  }
  if (r.target == display::PlaybackTarget::headless) out["final_max_um"] = r.final_max_um;
  if (r.latero_address) out["address"] = r.latero_address->text();
  if (r.latero_link) {
    const auto& l = *r.latero_link;
    const auto timing = display::summarize_timing(l, movie.rate_hz);
    using L = display::LateroLinkStats;
    put_fields(out, l, field("requests_sent", &L::requests_sent),
               field("replies_received", &L::replies_received),
               field("missed_replies", &L::missed_replies), field("late_replies", &L::late_replies),
               field("malformed_replies", &L::malformed_replies));
    out["achieved_rate_hz"] = timing.achieved_rate_hz;
    out["send_offset_p99_us"] = timing.offset_p99_us;
  }
  return out;
}

}  // namespace

void bind_play(py::module_& m) {
  def_with_kwargs(
      m, "play", &play, display::play_options(),
      "Plays a movie as `tactile play` does, without its emulator window: on an attached display\n"
      "(its vendor interface first), else headless into the emulated device; headless=True: the\n"
      "emulated device only; latero='HOST[:PORT]': that Latero (UDP; a movie of the `latero`\n"
      "layout) with the blade mapping blade_*. preview: a PNG strip of what the emulated device\n"
      "output (headless only; None: none). Prints what `tactile play` prints and returns what\n"
      "happened: target, the device's counters, for headless the largest |output| at the end\n"
      "(0 = at rest), for a Latero its address and the link's figures (requests_sent,\n"
      "replies_received, missed_replies, achieved_rate_hz, ...). Ctrl-C stops between two\n"
      "frames, every contactor ramped to rest, then raises KeyboardInterrupt. Keywords (the\n"
      "command line's options, with underscores):",
      py::arg("movie"));
}

}  // namespace tactile::python
