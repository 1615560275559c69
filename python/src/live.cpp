// live(source, ...): a live session into the emulated device, as `tactile live --headless`, its
// keywords made from the live request's option table; returns the summary as a dict. The
// session runs on its own thread while this one waits with the GIL released in short steps, so
// a KeyboardInterrupt (Ctrl-C, a notebook's stop) ends it cleanly with the device at rest.

#include <atomic>
#include <thread>

#include "bindings.hpp"
#include "request_kwargs.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/live/live_request.hpp"
#include "tactile/live/live_session.hpp"
#include "tactile/live/recording.hpp"

namespace tactile::python {

namespace {

py::dict summary_dict(const live::LiveSummary& s) {
  py::dict d;
  d["source"] = s.source;
  d["width_px"] = s.width_px;
  d["height_px"] = s.height_px;
  d["camera_rate_hz"] = s.camera_rate_hz;
  d["device_rate_hz"] = s.device_rate_hz;
  d["frames_in"] = s.frames_in;
  d["frames_processed"] = s.frames_processed;
  d["frames_dropped"] = s.frames_dropped;
  d["device_frames_sent"] = s.device_frames_sent;
  d["latency_p50_ms"] = s.latency_p50_ms;
  d["latency_p99_ms"] = s.latency_p99_ms;
  d["latency_max_ms"] = s.latency_max_ms;
  d["stopped"] = s.stopped;
  d["detector"] = s.detector;
  return d;
}

py::dict run_session(const std::string& source, const py::kwargs& kwargs) {
  live::LiveRequest request;
  request.source = source;
  set_from_kwargs(request, live::live_options(), kwargs, "live");
  const live::ResolvedLive session = live::resolve(request, OptionSpelling::python);
  display::EmulatedDevice device(live::emulated_display_options(session.layout));
  std::unique_ptr<live::SessionRecording> recording;
  if (session.record) recording = std::make_unique<live::SessionRecording>(*session.record);
  live::LiveCallbacks callbacks;
  if (recording) recording->attach(callbacks);
  std::atomic<bool> stop{false};
  live::SessionThread worker(session, device, stop, callbacks);
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
  return summary_dict(summary);
}

}  // namespace

void bind_live(py::module_& m) {
  // pybind11 keeps the pointer to the docstring: it must outlive the module.
  static const std::string doc =
      "A live session into the emulated device, as `tactile live SOURCE --headless`; returns\n"
      "its summary (frames in, processed, dropped, latency p50/p99/max in ms). Ctrl-C (or a\n"
      "notebook's stop) ends it with the device at rest. Keywords (the command line's options,\n"
      "with underscores):" +
      kwargs_doc(live::live_options());
  m.def("live", &run_session, py::arg("source"), doc.c_str());
}

}  // namespace tactile::python
