// `tactile live`: a camera, a stream, or a file played at its rate, through capture, strain and
// mapping to the display, frame by frame (live::run_live), recording as it goes.

#include <fmt/format.h>
#include <poll.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>
#include <vector>

#include "command.hpp"
#include "latero_cli.hpp"
#include "request_options.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/latero_transport.hpp"
#include "tactile/display/playback_plan.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile/display/viewer.hpp"
#include "tactile/live/live_request.hpp"
#include "tactile/live/live_session.hpp"
#include "tactile/live/recording.hpp"

namespace tactile::cli {

namespace {

namespace fs = std::filesystem;

// What the window shows, handed from the session's threads to the window's.
struct WindowState {
  std::mutex mutex;
  std::optional<display::CameraView> camera;
  std::vector<display::CameraEdge> edges;
  double full_scale = 0.01;
  std::vector<float> deflection_um;
  std::int64_t processed = 0, dropped = 0;
  double latency_ms = 0;
  double time_s = 0;
  bool over = false;
};

// The session on a thread of its own and the window on this one (GLFW's rule): the window
// shows the newest frame as received, the edges of the newest strain frame over it, the newest
// deflections as sent and the counts; closing it stops the session.
live::LiveSummary run_in_window(const live::ResolvedLive& session, display::Transport& device,
                                std::atomic<bool>& stop, live::LiveCallbacks callbacks,
                                const fs::path& screenshot) {
  WindowState state;
  state.deflection_um.assign(static_cast<std::size_t>(session.layout.contactor_count()), 0.0f);
  callbacks.received = [&, before = callbacks.received](std::int64_t frame, double time_s,
                                                        const capture::GrayImage& image) {
    before(frame, time_s, image);
    std::lock_guard lock(state.mutex);
    if (!state.camera) state.camera.emplace();
    state.camera->width_px = image.width_px;
    state.camera->height_px = image.height_px;
    state.camera->grey = image.pixels;
  };
  callbacks.strain = [&, before = callbacks.strain](const capture::StrainFrame& f) {
    before(f);
    std::unordered_map<std::int32_t, const capture::TrackedPoint*> at;
    for (const auto& p : f.points_to) at[p.track_id] = &p;
    std::vector<display::CameraEdge> edges;
    edges.reserve(f.edges.size());
    for (const auto& e : f.edges) {
      const auto a = at.find(e.track_a), b = at.find(e.track_b);
      if (a == at.end() || b == at.end()) continue;
      edges.push_back({static_cast<float>(a->second->x_px), static_cast<float>(a->second->y_px),
                       static_cast<float>(b->second->x_px), static_cast<float>(b->second->y_px),
                       static_cast<float>(e.rel_change)});
    }
    // Full colour at the 95th percentile of this frame's |strain| (a frame's strain is a rate:
    // its size depends on the camera's rate and the skin's speed).
    std::vector<double> size;
    for (const auto& e : edges) size.push_back(std::abs(e.strain));
    double full_scale = 1e-4;
    if (!size.empty()) {
      const auto k = size.begin() + static_cast<std::ptrdiff_t>(size.size() * 95 / 100);
      std::nth_element(size.begin(), k, size.end());
      full_scale = std::max(full_scale, *k);
    }
    std::lock_guard lock(state.mutex);
    state.edges = std::move(edges);
    state.full_scale = full_scale;
  };
  callbacks.mapped = [&, before = callbacks.mapped](std::int64_t frame,
                                                    const std::vector<float>& d) {
    before(frame, d);
    std::lock_guard lock(state.mutex);
    state.deflection_um = d;
  };
  callbacks.frame_done = [&, before = callbacks.frame_done](const live::FrameTiming& t) {
    before(t);
    std::lock_guard lock(state.mutex);
    (t.dropped ? state.dropped : state.processed) += 1;
    if (!t.dropped) state.latency_ms = t.latency_ms;
    state.time_s = t.source_time_s;
  };
  live::SessionThread worker(session, device, stop, callbacks, [&] {
    std::lock_guard lock(state.mutex);
    state.over = true;
  });
  display::ViewerResult shown;
  display::LiveViewerOptions options;
  options.keep_last_image = !screenshot.empty();
  // Strain of 1 % a frame in full colour: the edges' colours match the contactors'. Should the
  // window throw, `worker` stops the session and waits for it as it goes.
  shown = display::run_live_viewer(
      session.layout,
      [&]() -> std::optional<display::LiveFrame> {
        std::lock_guard lock(state.mutex);
        if (state.over) return std::nullopt;
        display::LiveFrame f;
        f.deflection_um = state.deflection_um;
        if (state.camera) {
          f.camera = *state.camera;
          f.camera->edges = state.edges;
          f.camera->full_scale = state.full_scale;
        }
        f.lines = {fmt::format("{}  t = {:.1f} s", session.source, state.time_s),
                   fmt::format("{} frames processed, {} dropped, latency {:.2f} ms",
                               state.processed, state.dropped, state.latency_ms)};
        return f;
      },
      options);
  stop = true;  // the window was closed, or the session ended
  const live::LiveSummary summary = worker.result();
  if (!screenshot.empty() && shown.last_image.width > 0) {
    display::write_png(screenshot, shown.last_image);
    fmt::print("live: wrote {}\n", screenshot.string());
  }
  return summary;
}

}  // namespace

void add_live(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  const auto [request, sub] = add_request_command<live::LiveRequest>(
      app, "live",
      "A live session: frames from a camera (/dev/videoN), a stream (udp://, tcp://, rtsp://)\n"
      "or a video file or folder of frames played at its rate as a camera would deliver it,\n"
      "each processed as it arrives (no look-ahead): landmarks followed by alignment, the\n"
      "strain of every edge between the last two frames, mapped onto the layout and sent to\n"
      "the display at its own rate (the newest frame held between camera frames). When the\n"
      "processing falls behind, the oldest waiting frame is dropped and counted. Prints frames\n"
      "in / processed / dropped and the latency (frame available -> its first device frame\n"
      "sent) p50/p99/max with the median of each stage. The display is where `tactile play`\n"
      "would play: an attached display over USB (libusb, else hidapi), else the emulator\n"
      "window when there is a screen, else the emulated device headless; or, by name, the\n"
      "emulated device (--headless, or --window to watch it: the camera image with the strain\n"
      "of every tracked edge drawn over it beside the contactors) or a Latero (--latero\n"
      "HOST[:PORT], with --layout latero).",
      live::live_options());
  // The output by name (the emulated device or a Latero), else play's choice (an attached
  // display first), said before the session starts.
  auto headless = std::make_shared<bool>(false);
  auto window = std::make_shared<bool>(false);
  auto screenshot = std::make_shared<fs::path>();
  auto latero = std::make_shared<display::LateroPlayTarget>();
  CLI::Option* headless_flag =
      sub->add_flag("--headless", *headless, "Play into the emulated device, with no window");
  CLI::Option* window_flag = sub->add_flag(
      "--window", *window,
      "Play into the emulated device and show the session in a window: the camera image\n"
      "with the strain of every tracked edge, the contactors, frames and latency (closing the\n"
      "window ends the session)");
  window_flag->excludes(headless_flag);
  sub->add_option("--screenshot", *screenshot,
                  "With --window: write the window's last image to this PNG when the session "
                  "ends")
      ->needs(window_flag);
  add_latero_play_options(*sub, *latero);
  sub->get_option("--latero")->excludes(headless_flag);
  sub->get_option("--latero")->excludes(window_flag);
  sub->callback([request, headless, window, screenshot, latero, &action] {
    action = WatchingStopSignals{[request, latero, headless, window, screenshot] {
      const live::ResolvedLive session = live::resolve(*request, OptionSpelling::cli);
      if (!screenshot->empty()) {
        refuse_output_over_input({output_file_ending("--screenshot", *screenshot, ".png")},
                                 {{"SOURCE", session.source}});
      }
      if (*window && !display::screen_available()) {
        throw RequestError("--window: no screen (DISPLAY or WAYLAND_DISPLAY) to open it on");
      }
      StopSignals signals;  // before any thread (libusb's too), so that they inherit the block
      std::unique_ptr<display::Transport> device;
      const display::EmulatedDevice* emulated = nullptr;
      // Where the emulated contactors ended, measured on the firmware's outputs once its ramp
      // to rest has had time to run (a stop ramps at the slew limit: well under a second).
      const auto say_where_it_rests = [&emulated] {
        if (!emulated) return;
        const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
        while (emulated->farthest_from_rest_um() > 0 && std::chrono::steady_clock::now() < until) {
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        fmt::print("live: the emulated device's outputs ended at most {:g} um from rest\n",
                   emulated->farthest_from_rest_um());
      };
      bool in_window = *window;
      if (!*headless && !*window && latero->address.empty()) {
        // Where `play` would play: an attached display (its vendor interface, else its HID
        // one), else the emulator window when there is a screen, else headless.
        const display::PlaybackPlan plan = display::plan_playback(
            false, display::list_usb_devices(), [] { return display::screen_available(); });
        if (plan.unopenable) fmt::print("live: {}", display::cannot_open(*plan.unopenable));
        if (plan.target == display::PlaybackTarget::device) {
          fmt::print("live: {}", display::streaming_to(*plan.device));
          device = display::open_usb_transport(*plan.device);
        } else {
          in_window = plan.target == display::PlaybackTarget::window;
          fmt::print("live: no display attached; {}\n",
                     in_window ? "opening the emulator window"
                               : "no screen either: playing headless into the emulated device");
        }
      }
      if (!latero->address.empty()) {
        live::require_latero_layout(session, OptionSpelling::cli);
        display::LateroTransportOptions options;
        options.mapping = latero->mapping;
        device = std::make_unique<display::LateroTransport>(
            display::parse_latero_address(latero->address), options);
      } else if (!device) {
        auto owned = std::make_unique<display::EmulatedDevice>(
            live::emulated_display_options(session.layout));
        emulated = owned.get();
        device = std::move(owned);
      }
      std::atomic<bool> stop{false};
      std::atomic<bool> over{false};
      std::thread watcher([&] {
        pollfd p{signals.fd(), POLLIN, 0};
        while (!over.load()) {
          if (::poll(&p, 1, 50) > 0) {
            stop = true;
            return;
          }
        }
      });
      std::unique_ptr<live::SessionRecording> recording;
      if (session.record) recording = std::make_unique<live::SessionRecording>(*session.record);
      live::LiveCallbacks callbacks;
      callbacks.note = [](const std::string& text) {
        fmt::print("live: {}\n", text);
        std::fflush(stdout);
      };
      auto last_print = std::chrono::steady_clock::now();
      std::int64_t processed = 0, dropped = 0;
      double last_latency_ms = 0;
      callbacks.frame_done = [&](const live::FrameTiming& t) {
        if (t.dropped) {
          ++dropped;
        } else {
          ++processed;
          last_latency_ms = t.latency_ms;
        }
        const auto now = std::chrono::steady_clock::now();
        if (now - last_print >= std::chrono::seconds(1)) {
          last_print = now;
          fmt::print("live: t = {:.1f} s, {} frames processed, {} dropped, latency {:.2f} ms\n",
                     t.source_time_s, processed, dropped, last_latency_ms);
          std::fflush(stdout);
        }
      };
      if (recording) recording->attach(callbacks);
      live::LiveSummary summary;
      try {
        if (in_window) {
          summary = run_in_window(session, *device, stop, callbacks, *screenshot);
        } else {
          summary = live::run_live(session, *device, stop, callbacks);
        }
      } catch (...) {
        over = true;
        watcher.join();
        // What was recorded stays: the CSV files are flushed before the error is reported.
        recording.reset();
        say_where_it_rests();
        throw;
      }
      over = true;
      watcher.join();
      if (recording) {
        recording->finish();
        const live::RecordedStrain strain = recording->strain_frames();
        fmt::print("live: recorded into {}{}\n", session.record->string(),
                   strain.left_out_of_h5 == 0
                       ? std::string()
                       : fmt::format("; strain.h5 holds {} of the {} strain frames measured (those "
                                     "across a dropped frame are in edges.csv only)",
                                     strain.measured - strain.left_out_of_h5, strain.measured));
      }
      fmt::print("{}", live::format_summary(summary));
      say_where_it_rests();
      if (const int signal = signals.received(); signal != 0) {
        fmt::print("live: stopped by {}; the display is at rest\n", stop_signal_name(signal));
        return exit_code_for_signal(signal);
      }
      return 0;
    }};
  });
}

}  // namespace tactile::cli
