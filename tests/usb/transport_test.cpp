// The libusb transport against a fake display on umockdev's fake USB bus (fake_display.hpp):
// enumerate, open, claim, stream, and unplug mid-stream. hidapi: hidraw_test.cpp.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <vector>

#include "fake_display.hpp"
#include "play_check.hpp"
#include "tactile/display/devices.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/display/player.hpp"
#include "tactile/display/usb_transports.hpp"

namespace tactile::display {
namespace {

std::optional<DeviceDescription> find(Backend backend) {
  for (const auto& d : list_usb_devices()) {
    if (d.backend == backend) return d;
  }
  return std::nullopt;
}

std::vector<std::uint8_t> frame(std::uint32_t seq) {
  std::vector<float> v(100);
  for (std::size_t i = 0; i < v.size(); ++i) v[i] = static_cast<float>((seq * 7 + i) % 81) - 40.f;
  return encode_frame(v, seq);
}

// Sends `frames` in order, waiting while the device has no room; returns the frames sent.
std::vector<std::vector<std::uint8_t>> stream(Transport& t, std::uint32_t first,
                                              std::uint32_t count) {
  std::vector<std::vector<std::uint8_t>> sent;
  for (std::uint32_t s = first; s < first + count; ++s) {
    sent.push_back(frame(s));
    while (!t.send_frame(sent.back())) t.wait(std::chrono::microseconds(200));
  }
  return sent;
}

void wait_received(Transport& t, std::uint64_t n) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (t.status().frames_received < n && std::chrono::steady_clock::now() < end) {
    t.wait(std::chrono::milliseconds(1));
  }
}

TEST(UsbLibusb, EnumeratesOpensAndStreamsExactlyTheEncodedFrames) {
  test::FakeDisplay fake;
  const auto device = find(Backend::libusb);
  ASSERT_TRUE(device.has_value()) << "libusb does not see the fake display";
  EXPECT_EQ(device->vendor_id, 0x1209);
  EXPECT_TRUE(device->accessible);
  EXPECT_EQ(device->product, "Tactile display");
  EXPECT_EQ(device->serial, "UMOCK-1");

  auto t = open_usb_transport(*device);
  const DeviceInfo info = t->info();
  EXPECT_EQ(info.backend, Backend::libusb);
  EXPECT_EQ(info.layout.rows, 10);
  EXPECT_EQ(info.layout.cols, 10);
  EXPECT_DOUBLE_EQ(info.layout.max_rate_hz, 1000);
  EXPECT_EQ(info.serial, "UMOCK-1");

  t->start(1000);
  const auto sent = stream(*t, 1, 300);  // more than the 64-frame FIFO: flow control works
  wait_received(*t, sent.size());
  const DeviceStatus s = t->status();
  EXPECT_EQ(s.frames_received, sent.size());
  EXPECT_EQ(s.malformed, 0u);
  EXPECT_EQ(fake.bulk_transfers(), sent);
  EXPECT_THROW(t->start(5000), TransportError);  // above the device's maximum: refused
  t->stop();
}

TEST(UsbLibusb, UnplugMidStreamIsAClearErrorWithinBoundedTime) {
  test::FakeDisplay fake;
  const auto device = find(Backend::libusb);
  ASSERT_TRUE(device.has_value());
  UsbTransportOptions options;
  options.timeout = std::chrono::milliseconds(500);
  auto t = open_usb_transport(*device, options);
  t->start(1000);
  stream(*t, 1, 50);
  fake.unplug();
  const auto t0 = std::chrono::steady_clock::now();
  std::string message;
  try {
    for (std::uint32_t s = 51; s < 100000; ++s) {
      const auto f = frame(s);
      while (!t->send_frame(f)) t->wait(std::chrono::microseconds(200));
    }
  } catch (const TransportError& e) {
    message = e.what();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("unplugged after %.3f s: %s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              message.c_str());
  EXPECT_NE(message.find("libusb"), std::string::npos) << message;
  EXPECT_NE(message.find("display at USB"), std::string::npos) << message;
  EXPECT_NE(message.find("unplugged"), std::string::npos) << message;
  // A generous bound: the point is that it ends (no hang), not how fast.
  EXPECT_LT(seconds, 5.0);
  EXPECT_THROW(t->status(), TransportError);
}

TEST(UsbLibusb, PluggedBackInTheNextStreamWorks) {
  {
    test::FakeDisplay fake;
    auto t = open_usb_transport(*find(Backend::libusb));
    t->start(1000);
    stream(*t, 1, 10);
    fake.unplug();
    EXPECT_THROW(stream(*t, 11, 1000), TransportError);
  }
  test::FakeDisplay again;
  const auto device = find(Backend::libusb);
  ASSERT_TRUE(device.has_value());
  auto t = open_usb_transport(*device);
  t->start(1000);
  const auto sent = stream(*t, 1, 20);
  wait_received(*t, sent.size());
  EXPECT_EQ(t->status().frames_received, sent.size());
  EXPECT_EQ(again.bulk_transfers(), sent);
}

TEST(UsbLibusb, PlayerStreamsAMovieDevicePaced) {
  test::FakeDisplay fake;
  auto t = open_usb_transport(*find(Backend::libusb));
  const PlaybackReport r = testing::play_and_check(*t);
  // Every frame the player sent crossed the bus as one transfer, in order.
  const auto transfers = fake.bulk_transfers();
  ASSERT_EQ(static_cast<std::int64_t>(transfers.size()), r.frames_sent);
  EXPECT_EQ(transfers.back()[5] & 1, 1);  // the last one is flagged end of stream
}

TEST(UsbLibusb, SigintMidPlayRampsTheFirmwareOutputsToRest) {
  StopSignals stop;  // before libusb starts its threads, as `tactile play` does
  test::FakeDisplay fake;
  auto t = open_usb_transport(*find(Backend::libusb));
  testing::play_and_signal(*t, stop, SIGINT);
  // Held at +20 um (200 wire units) until the signal; at rest once the player returned.
  for (const std::int16_t v : fake.outputs()) EXPECT_EQ(v, 0);
}

// A live session with the display on USB as its output: the frames reach the firmware, and it
// is left at rest when the session ends.
TEST(UsbLibusb, LiveSessionStreamsToTheDisplayAndLeavesItAtRest) {
  StopSignals stop;  // before libusb starts its threads, as `tactile live` does
  test::FakeDisplay fake;
  auto t = open_usb_transport(*find(Backend::libusb));
  testing::live_and_check(*t);
  for (const std::int16_t v : fake.outputs()) EXPECT_EQ(v, 0);
}

}  // namespace
}  // namespace tactile::display
