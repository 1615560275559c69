// `tactile live`: a camera, a stream, or a file played at its rate, through capture, strain and
// mapping to the display, frame by frame (live::run_live), recording as it goes.

#include <fmt/format.h>
#include <poll.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <memory>
#include <optional>
#include <thread>

#include "command.hpp"
#include "latero_cli.hpp"
#include "request_options.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/latero_transport.hpp"
#include "tactile/live/live_request.hpp"
#include "tactile/live/live_session.hpp"
#include "tactile/live/recording.hpp"

namespace tactile::cli {

void add_live(CLI::App& app, Action& action) {
  auto request = std::make_shared<live::LiveRequest>();
  // The output is asked for by name (the emulated device or a Latero), so that a session never
  // goes somewhere its user did not choose.
  auto headless = std::make_shared<bool>(false);
  auto latero = std::make_shared<display::LateroPlayTarget>();
  CLI::App* sub = app.add_subcommand(
      "live",
      "A live session: frames from a camera (/dev/videoN), a stream (udp://, tcp://, rtsp://)\n"
      "or a video file or folder of frames played at its rate as a camera would deliver it,\n"
      "each processed as it arrives (no look-ahead): landmarks followed by alignment, the\n"
      "strain of every edge between the last two frames, mapped onto the layout and sent to\n"
      "the display at its own rate (the newest frame held between camera frames). When the\n"
      "processing falls behind, the oldest waiting frame is dropped and counted. Prints frames\n"
      "in / processed / dropped and the latency (frame available -> its first device frame\n"
      "sent) p50/p99/max with the median of each stage. The display is the emulated device\n"
      "(--headless) or a Latero (--latero HOST[:PORT], with --layout latero); USB, hidapi\n"
      "and the window are not yet outputs of a live session.");
  add_request_options(*sub, request, live::live_options());
  CLI::Option* headless_flag =
      sub->add_flag("--headless", *headless, "Play into the emulated device, with no window");
  add_latero_play_options(*sub, *latero);
  sub->get_option("--latero")->excludes(headless_flag);
  sub->callback([request, headless, latero, &action] {
    if (!*headless && latero->address.empty()) {
      throw CLI::RequiredError("one of --headless (the emulated device) or --latero HOST[:PORT]");
    }
    action = [request, latero] {
      const live::ResolvedLive session = live::resolve(*request, OptionSpelling::cli);
      StopSignals signals;  // before any thread, so that they inherit the block
      std::unique_ptr<display::Transport> device;
      if (!latero->address.empty()) {
        // The Latero's own geometry: a movie of another layout would land on the wrong blades.
        if (session.layout.name != "latero") {
          throw RequestError(
              fmt::format("--latero plays the latero layout; give --layout latero "
                          "(not {})",
                          session.layout.name));
        }
        display::LateroTransportOptions options;
        options.mapping = latero->mapping;
        device = std::make_unique<display::LateroTransport>(
            display::parse_latero_address(latero->address), options);
      } else {
        device = std::make_unique<display::EmulatedDevice>(
            live::emulated_display_options(session.layout));
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
        summary = live::run_live(session, *device, stop, callbacks);
      } catch (...) {
        over = true;
        watcher.join();
        // What was recorded stays: the CSV files are flushed before the error is reported.
        recording.reset();
        throw;
      }
      over = true;
      watcher.join();
      if (recording) {
        recording->finish();
        fmt::print("live: recorded into {}\n", session.record->string());
      }
      fmt::print("{}", live::format_summary(summary));
      if (const int signal = signals.received(); signal != 0) {
        fmt::print("live: stopped by {}; the display is at rest\n",
                   signal == SIGINT ? "SIGINT" : "SIGTERM");
        return exit_code_for_signal(signal);
      }
      return 0;
    };
  });
}

}  // namespace tactile::cli
