// Device information and status replies: documented layout, round trip, bad lengths.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <vector>

#include "tactile_fw/control.h"

namespace {

tfw_config latero_config() {
  tfw_config c{};
  c.rows = 8;
  c.cols = 8;
  c.pitch_x_nm = 1200000;
  c.pitch_y_nm = 1612500;  // not a whole micrometre: why the reply uses nanometres
  c.contactor_width_nm = 500000;
  c.contactor_height_nm = 1400000;
  c.axis = 1;
  c.deflection_min = -1000;
  c.deflection_max = 900;
  c.max_slew_per_s = 200000;
  c.rate_hz = 1000;
  c.max_rate_hz = 1000;
  c.watchdog_timeout_ms = 5;
  return c;
}

TEST(Control, InfoRoundTripsAndFollowsTheDocumentedLayout) {
  auto dev = std::make_unique<tfw_device>();
  const tfw_config c = latero_config();
  ASSERT_EQ(tfw_device_init(dev.get(), &c, nullptr), TFW_CONFIG_OK);
  std::vector<std::uint8_t> bytes(TFW_INFO_BYTES + 5);
  ASSERT_EQ(tfw_encode_info(dev.get(), bytes.data(), TFW_INFO_BYTES - 1), 0u);
  ASSERT_EQ(tfw_encode_info(dev.get(), bytes.data(), bytes.size()), TFW_INFO_BYTES);
  EXPECT_EQ(bytes[0], TFW_PROTOCOL_VERSION);
  EXPECT_EQ(bytes[1], 1);  // axis y
  EXPECT_EQ(bytes[2], 8);
  EXPECT_EQ(bytes[6], static_cast<std::uint8_t>(-1000 & 0xFF));
  EXPECT_EQ(bytes[16] | bytes[17] << 8 | bytes[18] << 16 | bytes[19] << 24, 1612500);
  EXPECT_EQ(std::memcmp(bytes.data() + 36, TFW_FIRMWARE_VERSION, std::strlen(TFW_FIRMWARE_VERSION)),
            0);
  tfw_device_info info{};
  ASSERT_EQ(tfw_decode_info(bytes.data(), TFW_INFO_BYTES, &info), TFW_OK);
  EXPECT_EQ(info.config.rows, 8);
  EXPECT_EQ(info.config.pitch_y_nm, 1612500u);
  EXPECT_EQ(info.config.contactor_height_nm, 1400000u);
  EXPECT_EQ(info.config.axis, 1);
  EXPECT_EQ(info.config.deflection_min, -1000);
  EXPECT_EQ(info.config.deflection_max, 900);
  EXPECT_EQ(info.config.max_slew_per_s, 200000u);
  EXPECT_EQ(info.config.watchdog_timeout_ms, 5);
  EXPECT_EQ(info.fifo_capacity, TFW_FIFO_CAPACITY);
  EXPECT_STREQ(info.firmware_version, TFW_FIRMWARE_VERSION);
  EXPECT_EQ(tfw_decode_info(bytes.data(), TFW_INFO_BYTES + 1, &info), TFW_ERR_BAD_LENGTH);
  bytes[0] = 7;
  EXPECT_EQ(tfw_decode_info(bytes.data(), TFW_INFO_BYTES, &info), TFW_ERR_BAD_VERSION);
}

TEST(Control, StatusCarriesEveryCounter) {
  auto dev = std::make_unique<tfw_device>();
  const tfw_config c = latero_config();
  ASSERT_EQ(tfw_device_init(dev.get(), &c, nullptr), TFW_CONFIG_OK);
  ASSERT_EQ(tfw_device_start(dev.get(), 500), TFW_CONFIG_OK);
  std::vector<std::int16_t> v(64, 2000);  // beyond the range: clamped
  std::vector<std::uint8_t> frame(TFW_MAX_FRAME_BYTES);
  std::size_t len = 0;
  for (std::uint32_t s = 0; s < 3; ++s) {
    ASSERT_EQ(tfw_encode_frame(s, 0, v.data(), 64, frame.data(), frame.size(), &len), TFW_OK);
    ASSERT_EQ(tfw_device_receive(dev.get(), frame.data(), len), TFW_OK);
  }
  frame[0] ^= 1;
  EXPECT_EQ(tfw_device_receive(dev.get(), frame.data(), len), TFW_ERR_BAD_MAGIC);
  tfw_device_tick(dev.get());
  std::vector<std::uint8_t> bytes(TFW_STATUS_BYTES);
  ASSERT_EQ(tfw_encode_status(dev.get(), bytes.data(), bytes.size()), TFW_STATUS_BYTES);
  tfw_status_report r{};
  ASSERT_EQ(tfw_decode_status(bytes.data(), bytes.size(), &r), TFW_OK);
  tfw_status direct{};
  tfw_device_status(dev.get(), &direct);
  EXPECT_EQ(r.rate_hz, 500);
  EXPECT_EQ(r.status.state, TFW_STATE_STREAMING);
  EXPECT_EQ(r.status.fifo_fill, 2);
  EXPECT_EQ(r.status.frames_received, 3u);
  EXPECT_EQ(r.status.frames_played, 1u);
  EXPECT_EQ(r.status.clamped_samples, 64u);
  EXPECT_EQ(r.status.malformed_total, 1u);
  EXPECT_EQ(r.status.rejected[TFW_ERR_BAD_MAGIC], 1u);
  EXPECT_EQ(r.status.ticks, 1u);
  EXPECT_EQ(std::memcmp(&r.status.rejected, &direct.rejected, sizeof direct.rejected), 0);
  EXPECT_EQ(r.status.slew_limited_samples, direct.slew_limited_samples);
  EXPECT_EQ(tfw_decode_status(bytes.data(), bytes.size() - 1, &r), TFW_ERR_BAD_LENGTH);
}

}  // namespace
