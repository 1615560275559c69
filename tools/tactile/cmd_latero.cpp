// The Latero on the command line: options of play, probe, emulate and benchmark (latero_cli.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>
#include <thread>

#include "command.hpp"
#include "latero_cli.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "request_options.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/display/latero_emulator.hpp"
#include "tactile/display/latero_transport.hpp"
#include "tactile/display/play_request.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/viewer.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::cli {
namespace {

using Clock = std::chrono::steady_clock;

// The emulator served on a thread for as long as this lives.
class ServingThread {
 public:
  ServingThread(display::LateroEmulator& emulator, Clock::time_point until, int stop_fd = -1)
      : emulator_(emulator), thread_([this, until, stop_fd] { emulator_.serve(until, stop_fd); }) {}
  ~ServingThread() {
    emulator_.request_stop();
    thread_.join();
  }
  ServingThread(const ServingThread&) = delete;
  ServingThread& operator=(const ServingThread&) = delete;

 private:
  display::LateroEmulator& emulator_;
  std::thread thread_;
};

// Serves on a thread while the window (which must own the main thread) shows the blades as
// deflections through `mapping`, until the window closes, `until`, or a
// signal on `stop_fd`.
void show_live(display::LateroEmulator& emulator, const display::LateroBladeMapping& mapping,
               Clock::time_point until, int stop_fd) {
  const ServingThread server(emulator, until, stop_fd);
  const auto next = [&]() -> std::optional<display::LiveFrame> {
    if (Clock::now() >= until || stop_requested(stop_fd)) return std::nullopt;
    display::LiveFrame f;
    for (const std::uint8_t raw : emulator.blades()) {
      f.deflection_um.push_back(static_cast<float>(display::blade_deflection_um(raw, mapping)));
    }
    const auto c = emulator.counters();
    f.lines.push_back(fmt::format("emulated Latero on {} (UDP)", emulator.address()));
    f.lines.push_back(fmt::format("{} FULL (frames played), {} IO, {} RAW, {} malformed",
                                  c.full_requests, c.io_requests, c.raw_requests, c.malformed));
    f.lines.push_back(
        fmt::format("{} replies sent, {} left out; blades as deflection: raw {:g} "
                    "= centre, {:g} raw per {:g} um",
                    c.replies_sent, c.replies_dropped, mapping.centre_raw, mapping.raw_per_unit,
                    mapping.full_scale_um));
    return f;
  };
  display::run_live_viewer(movie::latero_layout(), next);
}

}  // namespace

CLI::Validator latero_address_check() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        try {
          display::parse_latero_address(text);
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
        return {};
      },
      "HOST[:PORT]");
}

void add_latero_play_options(CLI::App& play, display::LateroPlayTarget& o) {
  play.add_option("--latero", o.address,
                  "Play on the Latero at HOST[:PORT] (UDP, port 8900 by default)")
      ->check(latero_address_check());
  add_blade_mapping_options(play, o.mapping);
}

void add_blade_mapping_options(CLI::App& command, display::LateroBladeMapping& mapping) {
  // The options write into `mapping`, which outlives the parse (the caller's): no owner.
  add_request_options(
      command, std::shared_ptr<display::LateroBladeMapping>(std::shared_ptr<void>(), &mapping),
      display::blade_mapping_options());
}

int print_latero_device(const std::string& address) {
  display::LateroTransport latero(display::parse_latero_address(address));
  const display::LateroReply r = latero.probe();
  const auto buttons = [&](std::uint16_t mask) {
    return (r.dio_in & mask) == 0 ? "held" : "released";
  };
  fmt::print("latero  {}\n", latero.address().text());
  fmt::print("  {}\n", display::describe_controller_status(r.controller_status));
  fmt::print("  {}\n", display::describe_io_status(r.io_status));
  fmt::print("  buttons: left {}, right {} (dio_in 0x{:04X})\n",
             buttons(display::kLateroButton0Mask), buttons(display::kLateroButton1Mask), r.dio_in);
  fmt::print("  encoders {} {} {} {}; adc {} {} {} {}\n", r.encoder[0], r.encoder[1], r.encoder[2],
             r.encoder[3], r.adc[0], r.adc[1], r.adc[2], r.adc[3]);
  return 0;
}

void add_emulate(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    bool latero = false;
    display::LateroEmulatorOptions emulator;
    double seconds = 0;
    bool no_io_board = false;
    bool window = false;
    display::LateroBladeMapping mapping;  // how --window turns blade bytes into deflections
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "emulate",
      "Run an emulated device on the network. --latero: answer the OpenLatero UDP protocol as a\n"
      "Latero controller does (replies, status words, buttons), on 127.0.0.1 unless --bind says\n"
      "otherwise; malformed datagrams are counted and dropped. Prints its counters when it stops\n"
      "(Ctrl-C, or after --seconds).");
  sub->add_flag("--latero", opt->latero, "Emulate a Latero (the only device emulated so far)")
      ->required();
  add_ranged(*sub, "--port", opt->emulator.port, "UDP port (0: any free port, printed)", 0, 65535);
  sub->add_option("--bind", opt->emulator.bind_address, "Local address to answer on")
      ->capture_default_str();
  add_ranged(*sub, "--seconds", opt->seconds, "Stop after this long (0: until Ctrl-C)", 0.0,
             604800.0);
  add_ranged(*sub, "--drop-every", opt->emulator.drop_every_nth_reply,
             "Leave out every N-th reply (0: none), to test a client's loss accounting", 0,
             1000000);
  sub->add_flag("--no-io-board", opt->no_io_board,
                "Report no IO board (status 0), as a Latero with its IO board unplugged");
  sub->add_flag("--window", opt->window,
                "Show the emulated blades live in the viewer window (closing it stops)");
  add_blade_mapping_options(*sub, opt->mapping);
  sub->callback([opt, &action] {
    action = WatchingStopSignals{[opt] {
      if (opt->no_io_board) opt->emulator.io_status = 0;
      if (opt->window && !display::screen_available()) {
        throw std::runtime_error("--window: no screen (DISPLAY is unset or cannot be opened)");
      }
      display::LateroEmulator emulator(opt->emulator);
      StopSignals stop;  // before the serving and window threads, which inherit the block
      const int stop_fd = stop.fd();
      fmt::print("emulate: Latero answering on {} (UDP){}\n", emulator.address(),
                 opt->seconds > 0 ? fmt::format(" for {:g} s", opt->seconds) : ", Ctrl-C stops");
      std::fflush(stdout);
      const auto until = opt->seconds > 0
                             ? Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                                  std::chrono::duration<double>(opt->seconds))
                             : Clock::time_point::max();
      if (opt->window) {
        display::validate_blade_mapping(opt->mapping);
        show_live(emulator, opt->mapping, until, stop_fd);
      } else {
        emulator.serve(until, stop_fd);
      }
      // Taken, so that it does not end the process when the block is lifted: for the
      // emulator, Ctrl-C is the ordinary way to stop (exit 0 after its counters).
      stop.received();
      fmt::print("emulate: stopped\n{}", display::format_latero_counters(emulator.counters()));
      // Where the blades were left: a client that stopped cleanly leaves them all at centre.
      const auto blades = emulator.blades();
      const auto [lo, hi] = std::minmax_element(blades.begin(), blades.end());
      fmt::print("blades      left at raw {}..{}\n", *lo, *hi);
      return 0;
    }};
  });
}

void add_bench_latero(CLI::App& bench, Action& action, const std::string& /*command_line*/) {
  struct Options {
    double seconds = 10;
    // The layout's own rate: what a Latero plays at.
    double rate_hz = movie::latero_layout().max_rate_hz;
    std::uint32_t drop_every = 0;
  };
  const auto [opt, sub] = add_own_command<Options>(
      bench, "latero",
      "Play a movie on an emulated Latero over loopback UDP (127.0.0.1) and print the achieved\n"
      "rate, the send-time jitter, missed replies and the emulator's counters.");
  add_ranged(*sub, "--seconds", opt->seconds, "Length of the movie", 0.1, 600.0);
  add_ranged(*sub, "--rate-hz", opt->rate_hz, "Frame rate", 1.0,
             movie::latero_layout().max_rate_hz);
  add_ranged(*sub, "--drop-every", opt->drop_every, "Emulator leaves out every N-th reply", 0,
             1000000);
  sub->callback([opt, &action] {
    action = [opt] {
      display::LateroEmulatorOptions e;
      e.port = 0;
      e.drop_every_nth_reply = opt->drop_every;
      display::LateroEmulator emulator(e);

      movie::TactileMovie movie;
      movie.layout = movie::latero_layout();
      movie.rate_hz = opt->rate_hz;
      movie.frame_count = static_cast<std::int32_t>(std::lround(opt->seconds * opt->rate_hz));
      movie.deflection_um.resize(static_cast<std::size_t>(movie.frame_count) * 64);
      for (std::int32_t f = 0; f < movie.frame_count; ++f) {
        for (int k = 0; k < 64; ++k) {
          movie.frame(f)[static_cast<std::size_t>(k)] = static_cast<float>(
              80 * std::sin(2 * std::numbers::pi * (5.0 * f / opt->rate_hz + k / 64.0)));
        }
      }
      display::LateroLinkStats stats;
      display::PlaybackReport report;
      {
        const ServingThread server(emulator, Clock::time_point::max());
        display::LateroTransport latero({"127.0.0.1", emulator.port()});
        report = display::play_movie(movie, latero);
        stats = latero.stats();
      }
      const auto c = emulator.counters();
      fmt::print("bench latero: {} frames ({:g} s at {:g} Hz, {} of them ramps) to {}\n",
                 report.frames_sent, opt->seconds, opt->rate_hz, report.ramp_frames,
                 emulator.address());
      fmt::print("{}", display::format_latero_link(stats, opt->rate_hz));
      fmt::print("emulator\n{}", display::format_latero_counters(c));
      // The sender's view against the emulator's. The stream's requests are all FULL; the
      // probe before it is an IO request whose reply the emulator also counts.
      fmt::print(
          "agreement   FULL requests sent {} / received {}; replies sent {} / received {} + {} "
          "to the probe; left out {} / counted missed {} ({} of them late)\n",
          stats.requests_sent, c.full_requests, c.replies_sent, stats.replies_received,
          c.io_requests, c.replies_dropped, stats.missed_replies, stats.late_replies);
      return 0;
    };
  });
}

}  // namespace tactile::cli
