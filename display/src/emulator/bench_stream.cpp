#include "tactile/display/bench_stream.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <utility>

#include "tactile/common/stats.hpp"
#include "tactile/common/stopwatch.hpp"
#include "tactile/display/emulated_device.hpp"
#include "tactile/display/frame_codec.hpp"

namespace tactile::display {

namespace {

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

}  // namespace

// Fill the FIFO, let one tick pass, repeat: the wall-clock rate is the highest the host path
// sustains, whatever the array's own rate limit (10 kHz here, beyond any display's).
StreamThroughput measure_stream_throughput(int side, int frames) {
  const movie::Layout layout = square_layout(side, 10000);
  StreamThroughput out;
  out.side = side;
  const Patterns pattern(layout.contactor_count());
  out.frame_bytes = encode_frame(pattern(0), 1).size();
  const Stopwatch encoding;
  for (int f = 0; f < frames; ++f) {
    if (encode_frame(pattern(static_cast<std::uint32_t>(f)), f + 1).empty()) return out;
  }
  out.encode_cpu_us = 1e6 * encoding.cpu_s() / frames;

  EmulatedDeviceOptions options;
  options.layout = layout;
  options.record_outputs = false;
  EmulatedDevice device(options);
  device.start(layout.max_rate_hz);
  const auto tick = std::chrono::nanoseconds(static_cast<std::int64_t>(1e9 / layout.max_rate_hz));
  const Stopwatch delivery;
  for (int f = 0; f < frames;) {
    const auto bytes = encode_frame(pattern(static_cast<std::uint32_t>(f)), f + 1);
    while (!device.send_frame(bytes)) device.wait(tick);
    ++f;
  }
  out.total_cpu_us = 1e6 * delivery.cpu_s() / frames;
  out.frames_per_s = frames / delivery.wall_s();
  out.malformed = device.status().malformed;
  return out;
}

StreamPacing measure_stream_pacing(double rate_hz, double seconds) {
  const movie::Layout layout = square_layout(10, rate_hz);
  EmulatedDeviceOptions options;
  options.layout = layout;
  options.clock = EmulatedClock::real_time;
  options.record_outputs = false;
  EmulatedDevice device(options);
  StreamPacing out;
  out.rate_hz = rate_hz;
  out.seconds = seconds;
  const Patterns pattern(layout.contactor_count());
  const auto total = static_cast<std::uint32_t>(rate_hz * seconds);
  device.start(rate_hz);
  const Stopwatch run;
  std::uint32_t seq = 1;
  while (seq <= total) {
    const auto s = device.status();
    const std::uint32_t target = s.fifo_capacity / 2;
    if (s.fifo_fill < target) {
      for (std::uint32_t k = s.fifo_fill; k < target && seq <= total; ++k, ++seq) {
        const auto bytes = encode_frame(pattern(seq), seq, seq == total);
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
  out.cpu_per_frame_us = 1e6 * run.cpu_s() / total;
  device.stop();
  return out;
}

std::string stream_throughput_header(const std::vector<UsbLinkBudget>& links) {
  std::string line = fmt::format("{:<8} {:>6} {:>11} {:>11} {:>12}", "array", "bytes", "encode us",
                                 "host us", "max fps");
  for (const auto& l : links) line += fmt::format(" {:>16}", l.name + " Hz");
  return line + "\n";
}

std::string stream_throughput_row(const StreamThroughput& t,
                                  const std::vector<UsbLinkBudget>& links) {
  std::string line =
      fmt::format("{:<8} {:>6} {:>11.2f} {:>11.2f} {:>12.0f}", fmt::format("{}x{}", t.side, t.side),
                  t.frame_bytes, t.encode_cpu_us, t.total_cpu_us, t.frames_per_s);
  const auto contactors = static_cast<std::size_t>(t.side * t.side);
  for (const auto& l : links)
    line += fmt::format(" {:>16.0f}", usb_max_frame_rate_hz(l, contactors));
  return line + "\n";
}

std::string stream_throughput_note() {
  return "(host us: CPU per frame for encoding, delivery and the emulated firmware's tick; max "
         "fps: wall-clock rate the host path sustains; the USB columns are the bus limits of "
         "docs/protocol.md)\n";
}

std::string stream_pacing_report(const StreamPacing& p) {
  return fmt::format(
             "paced: 10x10 at {:g} Hz for {:g} s on a real-time emulated device, FIFO kept half "
             "full: {} frames played, {} underruns, {:.2f} us process CPU per frame (host and "
             "the emulator's clock thread)\n",
             p.rate_hz, p.seconds, p.played, p.underruns, p.cpu_per_frame_us) +
         fmt::format(
             "frame submission time (us): p50 {:.2f}  p90 {:.2f}  p99 {:.2f}  p99.9 {:.2f}  max "
             "{:.2f}\n",
             quantile(p.submit_us, 0.50), quantile(p.submit_us, 0.90), quantile(p.submit_us, 0.99),
             quantile(p.submit_us, 0.999), quantile(p.submit_us, 1.0));
}

}  // namespace tactile::display
