// The streaming benchmark's measurements as a library: every frame reaches the emulated
// firmware intact, the frame size is the protocol's (16-byte header + 2 bytes a contactor), and
// the report lines carry what was measured.

#include "tactile/display/bench_stream.hpp"

#include <gtest/gtest.h>

#include <string>

namespace td = tactile::display;

TEST(BenchStream, ThroughputDeliversEveryFrameIntactAtTheProtocolsSize) {
  const td::StreamThroughput t = td::measure_stream_throughput(8, 300);
  EXPECT_EQ(t.side, 8);
  EXPECT_EQ(t.frame_bytes, 16u + 2u * 64u);
  EXPECT_EQ(t.malformed, 0u);
  EXPECT_GT(t.frames_per_s, 0);
  EXPECT_GT(t.total_cpu_us, 0);
  const auto links = td::usb_link_budgets();
  const std::string row = td::stream_throughput_row(t, links);
  EXPECT_EQ(row.rfind("8x8", 0), 0u) << row;
  EXPECT_NE(row.find(" 144 "), std::string::npos) << row;
  // One column per link after the five of the array, in the header and in the row.
  const auto words = [](const std::string& s) {
    std::size_t n = 0;
    bool in = false;
    for (const char c : s) {
      if (c != ' ' && c != '\n' && !in) ++n;
      in = c != ' ' && c != '\n';
    }
    return n;
  };
  EXPECT_EQ(words(row), 5 + links.size());
}

TEST(BenchStream, PacedStreamPlaysEveryFrameAndReportsTheQuantiles) {
  const td::StreamPacing p = td::measure_stream_pacing(500, 0.2);
  EXPECT_EQ(p.played, 100u);
  EXPECT_EQ(p.submit_us.size(), 100u);
  const std::string report = td::stream_pacing_report(p);
  EXPECT_NE(report.find("at 500 Hz for 0.2 s"), std::string::npos) << report;
  EXPECT_NE(report.find("100 frames played"), std::string::npos) << report;
  EXPECT_NE(report.find("p99.9"), std::string::npos) << report;
}
