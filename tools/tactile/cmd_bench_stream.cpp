// `tactile bench stream`: the host side of streaming, measured through the in-process emulated
// device, and compared with the USB bandwidth budget of docs/protocol.md.

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <memory>
#include <vector>

#include "command.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "tactile/common/stats.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/display/usb_budget.hpp"

namespace tactile::cli {

namespace {

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

movie::Layout square_layout(int side, double max_rate_hz) {
  movie::Layout l = movie::stress_layout();
  l.name = fmt::format("{}x{}", side, side);
  l.rows = side;
  l.cols = side;
  l.max_rate_hz = max_rate_hz;
  return l;
}

// A pool of precomputed frames, so that pattern generation is not timed as host cost.
class Patterns {
 public:
  explicit Patterns(int contactors) {
    for (int f = 0; f < 64; ++f) {
      std::vector<float> v(static_cast<std::size_t>(contactors));
      for (int i = 0; i < contactors; ++i) {
        v[static_cast<std::size_t>(i)] = 40.f * std::sin(0.1f * static_cast<float>(f) + 0.3f * i);
      }
      pool_.push_back(std::move(v));
    }
  }
  const std::vector<float>& operator()(std::uint32_t f) const { return pool_[f % pool_.size()]; }

 private:
  std::vector<std::vector<float>> pool_;
};

struct Throughput {
  double encode_cpu_us = 0;  // host CPU per frame: encoding alone
  double total_cpu_us = 0;   // host CPU per frame: encode + deliver + emulated firmware
  double frames_per_s = 0;   // sustained through the emulated device (simulated clock)
  std::uint64_t malformed = 0;
};

// Pushes `frames` through a simulated-clock device as fast as the host can: fill the FIFO,
// let one tick pass, repeat. The wall-clock rate is the highest the host path sustains.
Throughput throughput(const movie::Layout& layout, int frames) {
  Throughput out;
  const Patterns pattern(layout.contactor_count());
  double t0 = process_cpu_s();
  for (int f = 0; f < frames; ++f) {
    const auto bytes = display::encode_frame(pattern(static_cast<std::uint32_t>(f)), f + 1);
    if (bytes.empty()) return out;
  }
  out.encode_cpu_us = 1e6 * (process_cpu_s() - t0) / frames;

  display::EmulatedDeviceOptions options;
  options.layout = layout;
  options.record_outputs = false;
  display::EmulatedDevice device(options);
  device.start(layout.max_rate_hz);
  const auto tick = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / layout.max_rate_hz));
  t0 = process_cpu_s();
  const double w0 = wall_seconds();
  for (int f = 0; f < frames;) {
    const auto bytes = display::encode_frame(pattern(static_cast<std::uint32_t>(f)), f + 1);
    while (!device.send_frame(bytes)) device.wait(tick);
    ++f;
  }
  const double wall = wall_seconds() - w0;
  out.total_cpu_us = 1e6 * (process_cpu_s() - t0) / frames;
  out.frames_per_s = frames / wall;
  out.malformed = device.status().malformed;
  return out;
}

struct Pacing {
  std::vector<double> submit_us;  // duration of each send_frame call
  std::uint64_t underruns = 0;
  std::uint64_t played = 0;
  double cpu_per_frame_us = 0;
};

// Real-time device at `rate_hz`, the host keeping its FIFO about half full from the status
// reports: the spread of submission times is what the player sees on a live device.
Pacing paced(const movie::Layout& layout, double rate_hz, double seconds) {
  display::EmulatedDeviceOptions options;
  options.layout = layout;
  options.clock = display::EmulatedClock::real_time;
  options.record_outputs = false;
  display::EmulatedDevice device(options);
  Pacing out;
  const Patterns pattern(layout.contactor_count());
  const auto total = static_cast<std::uint32_t>(rate_hz * seconds);
  device.start(rate_hz);
  const double c0 = process_cpu_s();
  std::uint32_t seq = 1;
  while (seq <= total) {
    const auto s = device.status();
    const std::uint32_t target = s.fifo_capacity / 2;
    if (s.fifo_fill < target) {
      for (std::uint32_t k = s.fifo_fill; k < target && seq <= total; ++k, ++seq) {
        const auto bytes = display::encode_frame(pattern(seq), seq, seq == total);
        const auto t0 = std::chrono::steady_clock::now();
        const bool ok = device.send_frame(bytes);
        out.submit_us.push_back(
            std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0)
                .count());
        if (!ok) break;
      }
    }
    device.wait(std::chrono::nanoseconds(static_cast<std::int64_t>(4e9 / rate_hz)));
  }
  device.wait(std::chrono::milliseconds(100));
  const auto s = device.status();
  out.underruns = s.underruns;
  out.played = s.frames_played;
  out.cpu_per_frame_us = 1e6 * (process_cpu_s() - c0) / total;
  device.stop();
  return out;
}

}  // namespace

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
      fmt::print("{:<8} {:>6} {:>11} {:>11} {:>12}", "array", "bytes", "encode us", "host us",
                 "max fps");
      for (const auto& l : links) fmt::print(" {:>16}", l.name + " Hz");
      fmt::print("\n");
      for (const int side : {4, 8, 10, 16}) {
        const auto layout = square_layout(side, 10000);
        const Throughput t = throughput(layout, opt->frames);
        const std::size_t n = static_cast<std::size_t>(side * side);
        fmt::print("{:<8} {:>6} {:>11.2f} {:>11.2f} {:>12.0f}", layout.name, 16 + 2 * n,
                   t.encode_cpu_us, t.total_cpu_us, t.frames_per_s);
        for (const auto& l : links) fmt::print(" {:>16.0f}", display::usb_max_frame_rate_hz(l, n));
        fmt::print("\n");
        if (t.malformed != 0) {
          throw std::runtime_error(fmt::format("{} frames were malformed", t.malformed));
        }
      }
      fmt::print(
          "(host us: CPU per frame for encoding, delivery and the emulated firmware's tick; "
          "max fps: wall-clock rate the host path sustains; the USB columns are the bus "
          "limits of docs/protocol.md)\n");

      const auto layout = square_layout(10, opt->rate_hz);
      const Pacing p = paced(layout, opt->rate_hz, opt->seconds);
      fmt::print(
          "paced: 10x10 at {:g} Hz for {:g} s on a real-time emulated device, FIFO kept half "
          "full: {} frames played, {} underruns, {:.2f} us process CPU per frame (host and the "
          "emulator's clock thread)\n",
          opt->rate_hz, opt->seconds, p.played, p.underruns, p.cpu_per_frame_us);
      fmt::print(
          "frame submission time (us): p50 {:.2f}  p90 {:.2f}  p99 {:.2f}  p99.9 {:.2f}  max "
          "{:.2f}\n",
          quantile(p.submit_us, 0.50), quantile(p.submit_us, 0.90), quantile(p.submit_us, 0.99),
          quantile(p.submit_us, 0.999), quantile(p.submit_us, 1.0));
      return 0;
    };
  });
}

}  // namespace tactile::cli
