#pragma once
// A live session: frames from a source through capture, strain and mapping to a display, one
// frame at a time, with no look-ahead.
//
// Threads: acquisition (reads the source; a file or folder is paced at its frame rate, each
// frame available at its time as from a camera) pushes into a DropOldestQueue; processing (the
// caller's thread) takes the oldest frame, follows the landmarks into it (AlignmentTracker,
// detecting new ones every detect_every frames), measures the strain of every edge between the
// last two frames (Delaunay, as the batch capture) and maps it onto the layout (the batch
// mapping's per-frame methods); the device feeder sends the newest mapped frame at the
// device's rate (zero-order hold: no interpolation, so no added delay) keeping its FIFO
// `fifo_target_frames` deep.
//
// Latency of a camera frame: from the moment it was available (a file's frame: its scheduled
// time; a camera: the driver's timestamp of its buffer where plausible, else its arrival; a
// stream: its arrival) to the first device frame carrying it leaving the host (send_frame
// returning).

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "tactile/capture/contact_map.hpp"
#include "tactile/capture/strain_movie.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/transport.hpp"
#include "tactile/live/live_request.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::live {

// One camera frame's fate and where its time went (milliseconds; processing stages are zero
// for a dropped frame).
struct FrameTiming {
  std::int64_t frame = 0;
  double source_time_s = 0;  // when it was available, from the session's start
  bool dropped = false;
  double wait_ms = 0;     // in the queue
  double track_ms = 0;    // detection and alignment
  double strain_ms = 0;   // triangulation
  double map_ms = 0;      // strain field and method
  double send_ms = 0;     // from mapped to its first device frame sent
  double latency_ms = 0;  // source_time to sent (NaN for a dropped frame)
  int points = 0;         // tracked into this frame from the one before
  int edges = 0;
};

struct LiveSummary {
  std::string source;
  int width_px = 0, height_px = 0;
  double camera_rate_hz = 0;
  double device_rate_hz = 0;
  std::int64_t frames_in = 0;
  std::int64_t frames_processed = 0;
  std::int64_t frames_dropped = 0;
  // Of frames_in, those whose time came from the camera driver's timestamp (the others: arrival,
  // or a rehearsal's schedule).
  std::int64_t frames_driver_stamped = 0;
  std::int64_t device_frames_sent = 0;
  double latency_p50_ms = 0, latency_p99_ms = 0, latency_max_ms = 0;
  // Medians of each stage over the processed frames.
  double wait_p50_ms = 0, track_p50_ms = 0, strain_p50_ms = 0, map_p50_ms = 0, send_p50_ms = 0;
  double median_points = 0;
  // Strain edges measured, and of them those left out at or beside skin out of contact.
  std::int64_t strain_edges = 0;
  std::int64_t strain_edges_near_gaps = 0;
  bool stopped = false;  // by a stop request (not the end of the source or of --seconds)
  std::string detector;  // the pore detector chosen on the first frame
  // The causal smoothing of tracks: the window in use at the end (positions fitted, 0: none),
  // the windows chosen along the way (empty when one was given) and the smallest and largest.
  int smoothing_frames = 0;
  int smoothing_choices = 0;
  int smoothing_min_frames = 0, smoothing_max_frames = 0;
  // The smoothing of steps across neighbouring tracks: the sigma in use at the end (mm, 0:
  // none), the choices along the way (none when one was given) and the smallest and largest.
  double neighbour_sigma_mm = 0;
  int neighbour_choices = 0;
  double neighbour_min_sigma_mm = 0, neighbour_max_sigma_mm = 0;
  // The least distance between tracked landmarks at the end (mm, 0: every landmark found), how
  // often the session changed it to keep up with the camera, and the largest it took.
  double min_spacing_mm = 0;
  int spacing_changes = 0;
  double max_spacing_mm = 0;
};

// What is known once the first frame has arrived.
struct SessionStart {
  std::string source;
  capture::Calibration calibration;  // of the frames' size
  double camera_rate_hz = 0;
  movie::Layout layout;
  double device_rate_hz = 0;
  capture::ContactGrid contact_grid;  // the cells each frame's contact is judged in
};

// One camera frame's contact as the session judged it when the frame came (contact_map.hpp):
// by the threshold of the frames seen so far.
struct FrameContact {
  std::int64_t frame = 0;
  double threshold_grey = 0;
  std::vector<double> ridge_contrast;  // per cell of SessionStart::contact_grid, row-major
  std::vector<std::uint8_t> in_contact;
};

// What the session hands out as it goes. `note` and `started` are called from the tracking
// thread; `frame_done`, `contact`, `strain` and `mapped` from the strain and mapping thread, which
// takes each tracked frame after `started` (so no two of these run at once, and none before
// `started`); `received` from the acquisition thread.
struct LiveCallbacks {
  std::function<void(const std::string&)> note = [](const std::string&) {};
  // Every camera frame as it arrives, processed or dropped later, at its time from the
  // session's start (called from the acquisition thread, the only one here that is).
  std::function<void(std::int64_t frame, double time_s, const capture::GrayImage&)> received =
      [](std::int64_t, double, const capture::GrayImage&) {};
  // Once, on the first frame, before any other call below.
  std::function<void(const SessionStart&)> started = [](const SessionStart&) {};
  // Every camera frame, processed or dropped, once its latency is known.
  std::function<void(const FrameTiming&)> frame_done = [](const FrameTiming&) {};
  // Every processed camera frame's contact, before its strain frame.
  std::function<void(const FrameContact&)> contact = [](const FrameContact&) {};
  // Every strain frame measured, with the tracked points of its two frames.
  std::function<void(const capture::StrainFrame&)> strain = [](const capture::StrainFrame&) {};
  // Every mapped frame (deflections, um, row-major).
  std::function<void(std::int64_t frame, const std::vector<float>&)> mapped =
      [](std::int64_t, const std::vector<float>&) {};
};

struct LiveOptions {
  int fifo_target_frames = 2;
  int threads = 0;  // alignment workers (0: one per core)
};

// Runs the session until the source ends, `seconds` pass or `stop` becomes true (then the
// device is stopped, which ramps it to rest). Throws tactile::FormatError naming the source when
// it cannot be opened or read (a camera removed mid-session: the frames so far were handed out
// and the device is at rest).
LiveSummary run_live(const ResolvedLive& session, display::Transport& device,
                     const std::atomic<bool>& stop, const LiveCallbacks& callbacks = {},
                     const LiveOptions& options = {});

// run_live on a thread of its own, for a caller whose thread must stay free while the session
// runs (a window, which GLFW keeps on the main thread; an interpreter answering Ctrl-C).
// `on_end` runs on the session's thread once run_live has returned or thrown. result() waits
// and returns the summary or rethrows what the session threw. An object destroyed while its
// session still runs (the caller is leaving on an exception) sets `stop` and waits, so the
// device is left at rest and no thread outlives what it uses.
class SessionThread {
 public:
  SessionThread(const ResolvedLive& session, display::Transport& device, std::atomic<bool>& stop,
                LiveCallbacks callbacks = {}, std::function<void()> on_end = {});
  SessionThread(const SessionThread&) = delete;
  SessionThread& operator=(const SessionThread&) = delete;
  ~SessionThread();

  // True once run_live has returned or thrown and on_end has run.
  bool done() const { return done_.load(); }
  // Waits for the session to end, without looking at how it ended.
  void wait();
  LiveSummary result();

 private:
  std::atomic<bool>& stop_;
  LiveSummary summary_;
  std::exception_ptr failure_;
  std::atomic<bool> done_{false};
  std::thread thread_;  // last: started once the members it uses exist
};

// The emulated device a session plays into when no display is named: the layout's own, on the
// real clock, recording nothing (a session may run for hours).
display::EmulatedDeviceOptions emulated_display_options(const movie::Layout& layout);

// The summary for a person: frames in / processed / dropped, latency p50/p99/max and the
// median of each stage.
std::string format_summary(const LiveSummary& summary);

// The calibration the session used for the frame size (from the file, or the uniform scale).
capture::Calibration session_calibration(const ResolvedLive& session, int width_px, int height_px);

}  // namespace tactile::live
