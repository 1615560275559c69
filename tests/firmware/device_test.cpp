// The device core: playout, malformed frames, clamp, slew limit, watchdog, FIFO full.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <random>
#include <vector>

#include "tactile_fw/device.h"
#include "target/device_config.h"

namespace {

// A STReSS-like device at 1 kHz: +-50 um, 10 um per tick slew, 5 ms watchdog (shared with the
// C checks that also run on QEMU).
tfw_config stress_config() {
  return tfw_test_stress_config();
}

struct Device {
  std::unique_ptr<tfw_device> dev = std::make_unique<tfw_device>();
  explicit Device(const tfw_config& c = stress_config()) {
    EXPECT_EQ(tfw_device_init(dev.get(), &c, nullptr), TFW_CONFIG_OK);
    EXPECT_EQ(tfw_device_start(dev.get(), 0), TFW_CONFIG_OK);
  }
  tfw_result send(std::uint32_t seq, const std::vector<std::int16_t>& v, std::uint8_t flags = 0) {
    auto b = bytes(seq, v, flags);
    return tfw_device_receive(dev.get(), b.data(), b.size());
  }
  static std::vector<std::uint8_t> bytes(std::uint32_t seq, const std::vector<std::int16_t>& v,
                                         std::uint8_t flags = 0) {
    std::vector<std::uint8_t> b(TFW_MAX_FRAME_BYTES);
    std::size_t len = 0;
    EXPECT_EQ(tfw_encode_frame(seq, flags, v.data(), static_cast<std::uint16_t>(v.size()), b.data(),
                               b.size(), &len),
              TFW_OK);
    b.resize(len);
    return b;
  }
  std::vector<std::int16_t> tick() {
    tfw_device_tick(dev.get());
    const std::int16_t* o = tfw_device_outputs(dev.get());
    return {o, o + 100};
  }
  tfw_status status() const {
    tfw_status s{};
    tfw_device_status(dev.get(), &s);
    return s;
  }
};

std::vector<std::int16_t> filled(std::int16_t v) {
  return std::vector<std::int16_t>(100, v);
}

TEST(DeviceConfig, RejectsInconsistentConfigs) {
  auto dev = std::make_unique<tfw_device>();
  tfw_config c = stress_config();
  c.rows = 0;
  EXPECT_EQ(tfw_device_init(dev.get(), &c, nullptr), TFW_CONFIG_BAD_SIZE);
  c = stress_config();
  c.rows = 20;
  c.cols = 20;  // 400 > TFW_MAX_CONTACTORS
  EXPECT_EQ(tfw_config_check(&c), TFW_CONFIG_BAD_SIZE);
  c = stress_config();
  c.deflection_min = 10;
  EXPECT_EQ(tfw_config_check(&c), TFW_CONFIG_BAD_RANGE);
  c = stress_config();
  c.rate_hz = 2000;
  EXPECT_EQ(tfw_config_check(&c), TFW_CONFIG_BAD_RATE);
  c = stress_config();
  c.max_slew_per_s = 10;
  EXPECT_EQ(tfw_config_check(&c), TFW_CONFIG_BAD_SLEW);
  c = stress_config();
  c.watchdog_timeout_ms = 0;
  EXPECT_EQ(tfw_config_check(&c), TFW_CONFIG_BAD_WATCHDOG);
  Device d;
  EXPECT_EQ(tfw_device_start(d.dev.get(), 1001), TFW_CONFIG_BAD_RATE);
}

TEST(Device, PlaysFramesInOrderOnePerTick) {
  Device d;
  for (std::uint32_t s = 0; s < 10; ++s) {
    ASSERT_EQ(d.send(s, filled(static_cast<std::int16_t>(10 * s))), TFW_OK);
  }
  for (std::uint32_t s = 0; s < 10; ++s) {
    const auto out = d.tick();
    EXPECT_EQ(out[0], 10 * s);  // steps of 1 um are within the slew limit
    EXPECT_EQ(d.status().last_sequence_played, s);
  }
  const auto st = d.status();
  EXPECT_EQ(st.frames_received, 10u);
  EXPECT_EQ(st.frames_played, 10u);
  EXPECT_EQ(st.underruns, 0u);
  EXPECT_EQ(st.state, TFW_STATE_STREAMING);
}

TEST(Device, MalformedFramesAreCountedByReasonAndNeverPlayed) {
  Device d;
  const std::int16_t poison = 333;  // only malformed frames carry this value
  std::uint32_t seq = 0;
  std::vector<std::vector<std::uint8_t>> bad;
  auto b = Device::bytes(100, filled(poison));
  b.back() ^= 1;
  bad.push_back(b);  // checksum
  b = Device::bytes(101, filled(poison));
  b.resize(b.size() - 1);
  bad.push_back(b);  // length
  b = Device::bytes(102, filled(poison));
  b[1] = 'X';
  bad.push_back(b);                                                          // magic
  bad.push_back(Device::bytes(103, std::vector<std::int16_t>(64, poison)));  // count
  ASSERT_EQ(d.send(seq++, filled(1)), TFW_OK);
  d.tick();
  EXPECT_EQ(tfw_device_receive(d.dev.get(), bad[0].data(), bad[0].size()), TFW_ERR_BAD_CHECKSUM);
  EXPECT_EQ(tfw_device_receive(d.dev.get(), bad[1].data(), bad[1].size()), TFW_ERR_BAD_LENGTH);
  EXPECT_EQ(tfw_device_receive(d.dev.get(), bad[2].data(), bad[2].size()), TFW_ERR_BAD_MAGIC);
  EXPECT_EQ(tfw_device_receive(d.dev.get(), bad[3].data(), bad[3].size()), TFW_ERR_BAD_COUNT);
  ASSERT_EQ(d.send(seq++, filled(2)), TFW_OK);
  EXPECT_EQ(d.send(seq - 1, filled(poison)), TFW_ERR_BAD_SEQUENCE);  // repeated
  EXPECT_EQ(d.send(seq - 2, filled(poison)), TFW_ERR_BAD_SEQUENCE);  // out of order
  ASSERT_EQ(d.send(seq++, filled(3)), TFW_OK);
  std::vector<std::int16_t> played;
  for (int t = 0; t < 30; ++t) {
    const auto out = d.tick();
    for (auto v : out) ASSERT_LT(v, 100) << "a malformed frame reached the outputs";
    played.push_back(out[0]);
  }
  EXPECT_EQ(played[0], 2);
  EXPECT_EQ(played[1], 3);
  const auto st = d.status();
  EXPECT_EQ(st.frames_played, 3u);
  EXPECT_EQ(st.malformed_total, 6u);
  EXPECT_EQ(st.rejected[TFW_ERR_BAD_CHECKSUM], 1u);
  EXPECT_EQ(st.rejected[TFW_ERR_BAD_LENGTH], 1u);
  EXPECT_EQ(st.rejected[TFW_ERR_BAD_MAGIC], 1u);
  EXPECT_EQ(st.rejected[TFW_ERR_BAD_COUNT], 1u);
  EXPECT_EQ(st.rejected[TFW_ERR_BAD_SEQUENCE], 2u);
}

TEST(Device, SequenceGapsAreAcceptedButCounted) {
  Device d;
  ASSERT_EQ(d.send(10, filled(0)), TFW_OK);
  ASSERT_EQ(d.send(11, filled(0)), TFW_OK);
  ASSERT_EQ(d.send(15, filled(0)), TFW_OK);
  EXPECT_EQ(d.status().sequence_gaps, 1u);
  // A new stream may start anywhere.
  ASSERT_EQ(tfw_device_start(d.dev.get(), 0), TFW_CONFIG_OK);
  EXPECT_EQ(d.send(3, filled(0)), TFW_OK);
}

TEST(Device, StoppedDeviceRefusesFramesAndRampsToNeutral) {
  Device d;
  for (std::uint32_t s = 0; s < 10; ++s) ASSERT_EQ(d.send(s, filled(500)), TFW_OK);
  for (int t = 0; t < 6; ++t) d.tick();
  EXPECT_EQ(d.tick()[0], 500);
  tfw_device_stop(d.dev.get());
  EXPECT_EQ(d.send(20, filled(500)), TFW_ERR_NOT_STARTED);
  std::int16_t prev = 500;
  for (int t = 0; t < 5; ++t) {
    const auto out = d.tick();
    EXPECT_EQ(out[0], prev - 100);  // ramps at the slew limit, never jumps
    prev = out[0];
  }
  EXPECT_EQ(prev, 0);
}

TEST(Device, ClampAndSlewHoldForRandomFrames) {
  Device d;
  const tfw_config c = stress_config();
  const std::int16_t slew = static_cast<std::int16_t>(c.max_slew_per_s / c.rate_hz);
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> wild(-2000, 2000);  // four times the range
  std::vector<std::int16_t> prev(100, 0);
  std::uint32_t seq = 0;
  bool saw_clamp = false, saw_slew = false;
  for (int t = 0; t < 3000; ++t) {
    std::vector<std::int16_t> v(100);
    for (auto& x : v) x = static_cast<std::int16_t>(wild(rng));
    ASSERT_EQ(d.send(seq++, v), TFW_OK);
    const auto out = d.tick();
    for (int i = 0; i < 100; ++i) {
      ASSERT_GE(out[i], c.deflection_min);
      ASSERT_LE(out[i], c.deflection_max);
      ASSERT_LE(std::abs(out[i] - prev[i]), slew);
      saw_clamp |= std::abs(v[i]) > 500;
      saw_slew |= std::abs(out[i] - prev[i]) == slew;
    }
    prev = out;
  }
  EXPECT_TRUE(saw_clamp);
  EXPECT_TRUE(saw_slew);
  const auto st = d.status();
  EXPECT_GT(st.clamped_samples, 0u);
  EXPECT_GT(st.slew_limited_samples, 0u);
  // Repeating one out-of-range frame long enough lands exactly on the clamp (from at most
  // +500 that takes 10 ticks at 100 units per tick).
  std::vector<std::int16_t> out;
  for (int t = 0; t < 11; ++t) {
    ASSERT_EQ(d.send(seq++, filled(-30000)), TFW_OK);
    out = d.tick();
  }
  EXPECT_EQ(out[0], c.deflection_min);
}

TEST(Device, WatchdogReachesNeutralWithin20msOfTheLastFrameAt1kHz) {
  Device d;
  std::uint32_t seq = 0;
  // Reach full deflection on every contactor, alternating sign.
  std::vector<std::int16_t> full(100);
  for (int i = 0; i < 100; ++i) full[i] = i % 2 ? 500 : -500;
  for (int t = 0; t < 10; ++t) {
    ASSERT_EQ(d.send(seq++, full), TFW_OK);
    d.tick();
  }
  ASSERT_EQ(d.tick()[1], 500);  // the FIFO ran dry: this tick is the first without a frame
  int ticks_to_neutral = 1;
  std::vector<std::int16_t> out = {1};
  while (std::any_of(out.begin(), out.end(), [](std::int16_t v) { return v != 0; })) {
    out = d.tick();
    ++ticks_to_neutral;
    ASSERT_LT(ticks_to_neutral, 100) << "never reached neutral";
  }
  EXPECT_LE(ticks_to_neutral, 20);  // 1 tick = 1 ms
  const auto st = d.status();
  EXPECT_EQ(st.watchdog_trips, 1u);
  EXPECT_EQ(st.state, TFW_STATE_IDLE);
  // The 5 starved ticks up to the trip (5 ms at 1 kHz) are underruns; after the trip the
  // stream is over and an empty FIFO is no longer an underrun.
  EXPECT_EQ(st.underruns, 5u);
  for (int t = 0; t < 50; ++t) d.tick();
  EXPECT_EQ(d.status().underruns, 5u);
}

TEST(Device, EndOfStreamFrameEndsWithoutUnderrunsOrTrip) {
  Device d;
  ASSERT_EQ(d.send(0, filled(50)), TFW_OK);
  ASSERT_EQ(d.send(1, filled(0), TFW_FLAG_END_OF_STREAM), TFW_OK);
  for (int t = 0; t < 40; ++t) d.tick();
  const auto st = d.status();
  EXPECT_EQ(st.frames_played, 2u);
  EXPECT_EQ(st.underruns, 0u);
  EXPECT_EQ(st.watchdog_trips, 0u);
}

TEST(Device, FullFifoRefusesThenAcceptsTheResentFrame) {
  Device d;
  std::uint32_t seq = 0;
  for (std::uint32_t i = 0; i < TFW_FIFO_CAPACITY; ++i) ASSERT_EQ(d.send(seq++, filled(7)), TFW_OK);
  EXPECT_FALSE(tfw_device_can_receive(d.dev.get()));
  EXPECT_EQ(d.status().fifo_fill, TFW_FIFO_CAPACITY);
  EXPECT_EQ(d.send(seq, filled(8)), TFW_ERR_FIFO_FULL);
  // A malformed frame is still reported as malformed, not as an overflow.
  auto b = Device::bytes(seq, filled(8));
  b[20] ^= 1;
  EXPECT_EQ(tfw_device_receive(d.dev.get(), b.data(), b.size()), TFW_ERR_BAD_CHECKSUM);
  d.tick();
  EXPECT_TRUE(tfw_device_can_receive(d.dev.get()));
  EXPECT_EQ(d.send(seq, filled(8)), TFW_OK);  // the same sequence number, resent
  const auto st = d.status();
  EXPECT_EQ(st.overflows, 1u);
  EXPECT_EQ(st.malformed_total, 1u);
  EXPECT_EQ(st.frames_received, TFW_FIFO_CAPACITY + 1u);
  EXPECT_EQ(st.sequence_gaps, 0u);
}

TEST(Device, HardwareCallbackSeesEveryTick) {
  struct Sink {
    int calls = 0;
    std::int16_t last = 0;
  } sink;
  tfw_hw hw{[](void* ctx, const std::int16_t* v, std::uint16_t n) {
              auto* s = static_cast<Sink*>(ctx);
              s->calls++;
              s->last = v[n - 1];
            },
            &sink};
  auto dev = std::make_unique<tfw_device>();
  const tfw_config c = stress_config();
  ASSERT_EQ(tfw_device_init(dev.get(), &c, &hw), TFW_CONFIG_OK);
  ASSERT_EQ(tfw_device_start(dev.get(), 0), TFW_CONFIG_OK);
  auto b = Device::bytes(0, filled(42));
  ASSERT_EQ(tfw_device_receive(dev.get(), b.data(), b.size()), TFW_OK);
  tfw_device_tick(dev.get());
  tfw_device_tick(dev.get());
  EXPECT_EQ(sink.calls, 2);
  EXPECT_EQ(sink.last, 42);
}

}  // namespace

namespace {

TEST(Device, RandomBytesAndCorruptedFramesNeverPlay) {
  // Random garbage and single-byte corruptions of valid frames: every one must be rejected
  // (a CRC-32 catches all single-byte errors) and nothing but the valid frames may play.
  Device d;
  std::mt19937 rng(1234);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uint32_t seq = 0;
  std::uint32_t accepted = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<std::uint8_t> b;
    if (trial % 2 == 0) {
      b.resize(rng() % 400);
      for (auto& x : b) x = static_cast<std::uint8_t>(byte(rng));
    } else {
      b = Device::bytes(seq + 1, filled(777));
      const std::size_t at = rng() % b.size();
      b[at] = static_cast<std::uint8_t>(b[at] ^ (1 + rng() % 255));
    }
    accepted += tfw_device_receive(d.dev.get(), b.data(), b.size()) == TFW_OK;
    if (trial % 10 == 0) {
      ASSERT_EQ(d.send(++seq, filled(static_cast<std::int16_t>(trial % 400))), TFW_OK);
    }
    const auto out = d.tick();
    // Valid frames stay below 400 units; a played corrupted frame would pull towards 500.
    for (auto v : out) ASSERT_LT(v, 400) << "corrupted frame played at trial " << trial;
  }
  EXPECT_EQ(accepted, 0u);
  const auto st = d.status();
  EXPECT_EQ(st.frames_received, 200u);
  EXPECT_EQ(st.malformed_total, 2000u);
}

}  // namespace
