// The hidapi transport (hidraw back end) against a fake display's hidraw node
// (fake_hidraw.hpp): enumerate, open, stream, unplug mid-stream, plug back in.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <thread>
#include <vector>

#include "fake_hidraw.hpp"
#include "play_check.hpp"
#include "tactile/display/devices.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/usb_transports.hpp"

namespace tactile::display {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::optional<DeviceDescription> find_hid() {
  for (const auto& d : list_usb_devices()) {
    if (d.backend == Backend::hidapi) return d;
  }
  return std::nullopt;
}

Bytes frame(std::uint32_t seq) {
  std::vector<float> v(100);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>((seq * 5 + i) % 71) - 35.f;
  return encode_frame(v, seq);
}

// docs/protocol.md, "HID interface": output report 1 of 63 bytes after the ID: flags (bit 0
// first chunk, bit 1 last), payload length 1..61, 61 payload bytes zero-padded.
std::vector<Bytes> reports_of(const Bytes& f) {
  std::vector<Bytes> out;
  for (std::size_t at = 0; at < f.size(); at += 61) {
    const std::size_t n = std::min<std::size_t>(61, f.size() - at);
    Bytes r(64, 0);
    r[0] = 1;
    r[1] = static_cast<std::uint8_t>((at == 0 ? 1 : 0) | (at + n == f.size() ? 2 : 0));
    r[2] = static_cast<std::uint8_t>(n);
    std::copy_n(f.begin() + static_cast<std::ptrdiff_t>(at), n, r.begin() + 3);
    out.push_back(r);
  }
  return out;
}

std::vector<Bytes> stream(Transport& t, std::uint32_t first, std::uint32_t count) {
  std::vector<Bytes> sent;
  for (std::uint32_t s = first; s < first + count; ++s) {
    sent.push_back(frame(s));
    while (!t.send_frame(sent.back())) t.wait(std::chrono::microseconds(200));
  }
  return sent;
}

std::vector<Bytes> reports_of_all(const std::vector<Bytes>& frames) {
  std::vector<Bytes> out;
  for (const auto& f : frames) {
    for (auto& r : reports_of(f)) out.push_back(std::move(r));
  }
  return out;
}

TEST(UsbHidraw, EnumeratesTheDisplayFromSysfs) {
  test::FakeHidraw fake;
  const auto device = find_hid();
  ASSERT_TRUE(device.has_value()) << "hidapi does not see the fake hidraw display";
  EXPECT_EQ(device->vendor_id, 0x1209);
  EXPECT_EQ(device->product_id, 0x0001);
  EXPECT_EQ(device->interface_number, 1);
  EXPECT_EQ(device->path, test::FakeHidraw::kDevnode);
  EXPECT_EQ(device->manufacturer, "tactile-movies");
  EXPECT_EQ(device->product, "Tactile display");
  EXPECT_EQ(device->serial, "UMOCK-HID-1");
  EXPECT_TRUE(device->accessible);
}

TEST(UsbHidraw, OpensAndTheDeviceReceivesExactlyTheEncodedFramesInReports) {
  test::FakeHidraw fake;
  const auto device = find_hid();
  ASSERT_TRUE(device.has_value());
  auto t = open_usb_transport(*device);
  const DeviceInfo info = t->info();  // a GET_REPORT feature request answered by the firmware
  EXPECT_EQ(info.backend, Backend::hidapi);
  EXPECT_EQ(info.layout.rows, 10);
  EXPECT_EQ(info.layout.cols, 10);
  EXPECT_DOUBLE_EQ(info.layout.max_rate_hz, 1000);
  EXPECT_EQ(info.fifo_capacity_frames, 64u);

  t->start(1000);
  const auto sent = stream(*t, 1, 150);  // more than the 64-frame FIFO: the writes wait
  const DeviceStatus s = t->status();
  EXPECT_EQ(s.frames_received, sent.size());
  EXPECT_EQ(s.malformed, 0u);
  EXPECT_TRUE(s.started);
  const auto reports = fake.output_reports();
  EXPECT_EQ(reports.size(), sent.size() * 4);  // 216-byte frames: 4 reports each
  EXPECT_EQ(reports, reports_of_all(sent));
  EXPECT_THROW(t->start(5000), TransportError);  // above the device's maximum: stalled
  t->stop();
}

TEST(UsbHidraw, UnplugMidStreamEndsTheStreamWithAClearErrorWithinBoundedTime) {
  test::FakeHidraw fake;
  const auto device = find_hid();
  ASSERT_TRUE(device.has_value());
  auto t = open_usb_transport(*device);
  t->start(1000);
  // Pull the plug from another thread while the host is blocked in a write (the FIFO is full
  // after 64 frames; 100 000 frames at 1 kHz would take 100 s).
  std::atomic<std::int64_t> unplugged_ns{0};
  std::thread puller([&] {
    while (fake.output_reports().size() < 4 * 200) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    unplugged_ns = std::chrono::steady_clock::now().time_since_epoch().count();
    fake.unplug();
  });
  std::string message;
  try {
    stream(*t, 1, 100000);
  } catch (const TransportError& e) {
    message = e.what();
  }
  const auto failed_ns = std::chrono::steady_clock::now().time_since_epoch().count();
  puller.join();
  const double seconds = static_cast<double>(failed_ns - unplugged_ns.load()) * 1e-9;
  std::printf("hidraw unplugged; stream ended %.4f s later: %s\n", seconds, message.c_str());
  EXPECT_NE(message.find("hidapi"), std::string::npos) << message;
  EXPECT_NE(message.find(device->path), std::string::npos) << message;
  EXPECT_NE(message.find("No such device"), std::string::npos) << message;
  EXPECT_NE(message.find("unplugged"), std::string::npos) << message;
  EXPECT_GE(seconds, 0.0);
  EXPECT_LT(seconds, 1.0);
  EXPECT_THROW(t->status(), TransportError);
  EXPECT_FALSE(find_hid().has_value()) << "the removed display is still listed";
}

TEST(UsbHidraw, PluggedBackInTheNextStreamWorks) {
  {
    test::FakeHidraw fake;
    auto t = open_usb_transport(*find_hid());
    t->start(1000);
    stream(*t, 1, 10);
    fake.unplug();
    EXPECT_THROW(stream(*t, 11, 10), TransportError);
  }
  test::FakeHidraw again;
  const auto device = find_hid();
  ASSERT_TRUE(device.has_value());
  auto t = open_usb_transport(*device);
  t->start(1000);
  const auto sent = stream(*t, 1, 20);
  EXPECT_EQ(t->status().frames_received, sent.size());
  EXPECT_EQ(again.output_reports(), reports_of_all(sent));
}

TEST(UsbHidraw, PlayerStreamsAMovieDevicePaced) {
  test::FakeHidraw fake;
  auto t = open_usb_transport(*find_hid());
  const PlaybackReport r = testing::play_and_check(*t);
  const auto reports = fake.output_reports();
  ASSERT_EQ(static_cast<std::int64_t>(reports.size()), 4 * r.frames_sent);
  EXPECT_EQ(reports[reports.size() - 4][0], 1);
  // The last frame is flagged end of stream: byte 5 of the frame, the 3rd payload byte + 3.
  EXPECT_EQ(reports[reports.size() - 4][3 + 5] & 1, 1);
}

TEST(UsbHidraw, SigtermMidPlayRampsTheFirmwareOutputsToRest) {
  StopSignals stop;
  test::FakeHidraw fake;
  auto t = open_usb_transport(*find_hid());
  testing::play_and_signal(*t, stop, SIGTERM);
  for (const std::int16_t v : fake.outputs()) EXPECT_EQ(v, 0);
}

TEST(UsbHidraw, LiveSessionStreamsToTheDisplayAndLeavesItAtRest) {
  StopSignals stop;
  test::FakeHidraw fake;
  auto t = open_usb_transport(*find_hid());
  testing::live_and_check(*t);
  for (const std::int16_t v : fake.outputs()) EXPECT_EQ(v, 0);
}

}  // namespace
}  // namespace tactile::display
