#pragma once
// `tactile bench stream` as a library: the host side of streaming measured through the
// in-process emulated device (encoding, delivery and the emulated firmware's tick), a real-time
// paced stream's submission times, and the report lines that set both beside the USB budget
// (usb_budget.hpp). The command line only parses, calls and prints.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "tactile/display/usb_budget.hpp"

namespace tactile::display {

// One square array pushed through a simulated-clock device as fast as the host can.
struct StreamThroughput {
  int side = 0;                 // contactors per row and per column
  std::size_t frame_bytes = 0;  // one frame on the wire
  double encode_cpu_us = 0;     // host CPU per frame: encoding alone
  double total_cpu_us = 0;      // host CPU per frame: encode + deliver + emulated firmware
  double frames_per_s = 0;      // wall-clock rate the host path sustains
  std::uint64_t malformed = 0;  // frames the emulated firmware refused (should be none)
};

// A 10 x 10 array on a real-time device at `rate_hz`, the host keeping its FIFO half full from
// the status reports: the spread of submission times is what a player sees on a live device.
struct StreamPacing {
  double rate_hz = 0;
  double seconds = 0;
  std::vector<double> submit_us;  // duration of each send_frame call
  std::uint64_t underruns = 0;
  std::uint64_t played = 0;
  double cpu_per_frame_us = 0;  // process CPU (host and the emulator's clock thread)
};

// The array sides the benchmark measures.
inline constexpr int kStreamBenchSides[] = {4, 8, 10, 16};

StreamThroughput measure_stream_throughput(int side, int frames);
StreamPacing measure_stream_pacing(double rate_hz, double seconds);

// The throughput table: header, one line per array (with each USB link's limit for it), and the
// note that says what the columns are. Lines end with a newline.
std::string stream_throughput_header(const std::vector<UsbLinkBudget>& links);
std::string stream_throughput_row(const StreamThroughput& t,
                                  const std::vector<UsbLinkBudget>& links);
std::string stream_throughput_note();
// The paced stream's two lines: frames, underruns and CPU; submission time quantiles.
std::string stream_pacing_report(const StreamPacing& p);

}  // namespace tactile::display
