// `tactile bench stream`: the host side of streaming, measured through the in-process emulated
// device (display/bench_stream.hpp), and compared with the USB bandwidth budget of
// docs/protocol.md.

#include <fmt/format.h>

#include <memory>
#include <stdexcept>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "tactile/display/bench_stream.hpp"
#include "tactile/display/usb_budget.hpp"

namespace tactile::cli {

void add_bench_stream(CLI::App& bench, Action& action, const std::string& /*command_line*/) {
  struct Options {
    int frames = 20000;
    double seconds = 2.0;
    double rate_hz = 1000;
  };
  const auto [opt, sub] = add_own_command<Options>(
      bench, "stream",
      "Host CPU time per frame, highest sustained frame rate through the emulated device,\n"
      "spread of frame submission times on a real-time device, against the USB budget.");
  add_ranged(*sub, "--frames", opt->frames, "Frames pushed per array size for the throughput", 100,
             10000000);
  add_ranged(*sub, "--seconds", opt->seconds, "Length of the real-time paced stream", 0.1, 600.0);
  add_ranged(*sub, "--rate-hz", opt->rate_hz, "Rate of the real-time paced stream (Hz)", 1.0,
             10000.0);
  sub->callback([opt, &action] {
    action = [opt] {
      const auto links = display::usb_link_budgets();
      fmt::print(
          "bench stream: {} frames per array through the emulated device (simulated clock)\n",
          opt->frames);
      fmt::print("{}", display::stream_throughput_header(links));
      for (const int side : display::kStreamBenchSides) {
        const auto t = display::measure_stream_throughput(side, opt->frames);
        fmt::print("{}", display::stream_throughput_row(t, links));
        if (t.malformed != 0) {
          throw std::runtime_error(fmt::format("{} frames were malformed", t.malformed));
        }
      }
      fmt::print("{}", display::stream_throughput_note());
      fmt::print("{}", display::stream_pacing_report(
                           display::measure_stream_pacing(opt->rate_hz, opt->seconds)));
      return 0;
    };
  });
}

}  // namespace tactile::cli
