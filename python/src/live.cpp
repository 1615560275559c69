// live(source, ...): a live session as `tactile live` runs it (an attached display, a Latero or
// the emulated device), its keywords made from the live request's option table and play's for
// the output; returns the summary as a dict. The
// session runs on its own thread while this one waits with the GIL released in short steps, so
// a KeyboardInterrupt (Ctrl-C, a notebook's stop) ends it cleanly with the device at rest.

#include <atomic>
#include <thread>

#include "bindings.hpp"
#include "request_kwargs.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/latero_transport.hpp"
#include "tactile/display/play_request.hpp"
#include "tactile/display/playback_plan.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile/live/live_request.hpp"
#include "tactile/live/live_session.hpp"
#include "tactile/live/recording.hpp"

namespace tactile::python {

namespace {

py::dict summary_dict(const live::LiveSummary& s) {
  using S = live::LiveSummary;
  py::dict d;
  put_fields(
      d, s, field("source", &S::source), field("width_px", &S::width_px),
      field("height_px", &S::height_px), field("camera_rate_hz", &S::camera_rate_hz),
      field("device_rate_hz", &S::device_rate_hz), field("frames_in", &S::frames_in),
      field("frames_processed", &S::frames_processed), field("frames_dropped", &S::frames_dropped),
      field("device_frames_sent", &S::device_frames_sent),
      field("latency_p50_ms", &S::latency_p50_ms), field("latency_p99_ms", &S::latency_p99_ms),
      field("latency_max_ms", &S::latency_max_ms), field("median_points", &S::median_points),
      field("strain_edges", &S::strain_edges),
      field("strain_edges_near_gaps", &S::strain_edges_near_gaps), field("stopped", &S::stopped),
      field("detector", &S::detector));
  return d;
}

// The output's keywords are play's (headless, latero, blade_*), read with play's table so that
// they mean and are checked the same; the others are the live request's.
bool output_keyword(const std::string& name) {
  return name == "headless" || name == "latero" || name.rfind("blade_", 0) == 0;
}

py::dict run_session(const std::string& source, const py::kwargs& kwargs) {
  py::kwargs session_kwargs, output_kwargs;
  for (const auto& [key, value] : kwargs) {
    (output_keyword(key.cast<std::string>()) ? output_kwargs : session_kwargs)[key] = value;
  }
  live::LiveRequest request;
  request.source = source;
  set_from_kwargs(request, live::live_options(), session_kwargs, "live");
  const live::ResolvedLive session = live::resolve(request, OptionSpelling::python);
  display::PlayRequest output_request;
  set_from_kwargs(output_request, display::play_options(), output_kwargs, "live");
  const display::ResolvedPlay output = display::resolve(output_request, OptionSpelling::python);
  // Where `tactile live` plays: the Latero named, else an attached display (no window here:
  // the module links no GUI), else the emulated device. A device that cannot take the session's
  // layout is refused by the session before it starts.
  std::unique_ptr<display::Transport> device;
  std::string target = "headless";
  if (output.latero) {
    live::require_latero_layout(session, OptionSpelling::python);
    display::LateroTransportOptions options;
    options.mapping = output.latero->mapping;
    device = std::make_unique<display::LateroTransport>(
        display::parse_latero_address(output.latero->address), options);
    target = "latero";
  } else if (!output.headless) {
    const display::PlaybackPlan plan =
        display::plan_playback(false, display::list_usb_devices(), [] { return false; });
    if (plan.target == display::PlaybackTarget::device) {
      device = display::open_usb_transport(*plan.device);
      target = "device";
    }
  }
  if (!device) {
    device =
        std::make_unique<display::EmulatedDevice>(live::emulated_display_options(session.layout));
  }
  std::unique_ptr<live::SessionRecording> recording;
  if (session.record) recording = std::make_unique<live::SessionRecording>(*session.record);
  live::LiveCallbacks callbacks;
  if (recording) recording->attach(callbacks);
  std::atomic<bool> stop{false};
  live::SessionThread worker(session, *device, stop, callbacks);
  while (!worker.done()) {
    {
      py::gil_scoped_release unlocked;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (PyErr_CheckSignals() != 0) {
      stop = true;
      {
        py::gil_scoped_release unlocked;
        worker.wait();
      }
      throw py::error_already_set();
    }
  }
  const live::LiveSummary summary = worker.result();
  if (recording) {
    recording->finish();
  }
  py::dict d = summary_dict(summary);
  d["target"] = target;
  return d;
}

}  // namespace

void bind_live(py::module_& m) {
  def_with_kwargs(
      m, "live", &run_session, live::live_options(),
      "A live session as `tactile live SOURCE` runs it, without its window: on an attached\n"
      "display (its vendor interface first), else into the emulated device; headless=True: the\n"
      "emulated device only; latero='HOST[:PORT]' (with layout='latero'): that Latero, with\n"
      "the blade mapping blade_* as play() takes them. Returns its summary (target, frames in,\n"
      "processed, dropped, latency p50/p99/max in ms). Ctrl-C (or a notebook's stop) ends it\n"
      "with the device at rest. Keywords (the command line's options, with underscores):",
      py::arg("source"));
}

}  // namespace tactile::python
