#include "fake_firmware.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "device_config.h"  // tests/firmware/target: the STReSS-like test device

namespace tactile::test {

FakeFirmware::FakeFirmware(const char* serial) {
  const tfw_config config = tfw_test_stress_config();
  if (tfw_device_init(&dev_, &config, nullptr) != TFW_CONFIG_OK) {
    throw std::logic_error("fake firmware: bad configuration");
  }
  const tfw_usb_dcd dcd{this, &dcd_write, &dcd_stall, &dcd_ready};
  tfw_usb_init(&usb, &dev_, &dcd, TFW_USB_FULL_SPEED, serial);
  // The kernel configures a device when it enumerates it; do the same.
  const std::uint8_t set_configuration[8] = {0x00, 9, 1, 0, 0, 0, 0, 0};
  tfw_usb_setup(&usb, set_configuration, nullptr, 0);
}

int FakeFirmware::dcd_write(void* context, std::uint8_t ep, const std::uint8_t* data,
                            std::uint16_t len) {
  auto* self = static_cast<FakeFirmware*>(context);
  if (ep == 0x80) self->ep0_reply_.assign(data, data + len);
  if (ep == TFW_USB_EP_HID_IN) self->hid_in_.assign(data, data + len);
  return 1;
}

void FakeFirmware::dcd_stall(void* context, std::uint8_t) {
  static_cast<FakeFirmware*>(context)->ep0_stalled_ = true;
}

void FakeFirmware::dcd_ready(void* context, std::uint8_t ep, int ready) {
  static_cast<FakeFirmware*>(context)->ready_[ep & 3] = ready != 0;
}

int FakeFirmware::control(const std::uint8_t setup[8], std::uint8_t* data) {
  const auto w_length = static_cast<std::uint16_t>(setup[6] | (setup[7] << 8));
  const bool in = (setup[0] & 0x80) != 0;
  ep0_reply_.clear();
  ep0_stalled_ = false;
  tfw_usb_setup(&usb, setup, in ? nullptr : data, in ? 0 : w_length);
  if (ep0_stalled_) return -1;
  if (!in) return w_length;
  const std::size_t n = std::min<std::size_t>(ep0_reply_.size(), w_length);
  std::memcpy(data, ep0_reply_.data(), n);
  return static_cast<int>(n);
}

void FakeFirmware::advance() {
  const auto now = std::chrono::steady_clock::now();
  const double period_s = 1.0 / dev_.config.rate_hz;
  int ticks = 0;
  while (std::chrono::duration<double>(now - last_tick_).count() >= period_s && ticks < 100) {
    tfw_usb_tick(&usb);
    last_tick_ += std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(period_s));
    ++ticks;
  }
  if (ticks == 100) last_tick_ = now;
}

std::vector<std::int16_t> FakeFirmware::outputs() const {
  const std::int16_t* out = tfw_device_outputs(&dev_);
  return {out, out + tfw_device_contactor_count(&dev_)};
}

std::vector<std::uint8_t> FakeFirmware::take_hid_in() {
  std::vector<std::uint8_t> out;
  out.swap(hid_in_);
  return out;
}

std::string FakeFirmware::descriptors_hex() {
  static const char* digits = "0123456789abcdef";
  std::string s;
  for (const std::uint8_t type : {TFW_USB_DESC_DEVICE, TFW_USB_DESC_CONFIGURATION}) {
    const std::uint8_t* d = nullptr;
    const std::uint16_t n = tfw_usb_descriptor(&usb, type, 0, &d);
    for (std::uint16_t i = 0; i < n; ++i) {
      s += digits[d[i] >> 4];
      s += digits[d[i] & 15];
    }
  }
  return s;
}

std::vector<std::uint8_t> FakeFirmware::hid_report_descriptor() {
  const std::uint8_t* d = nullptr;
  const std::uint16_t n = tfw_usb_descriptor(&usb, TFW_USB_DESC_HID_REPORT, 0, &d);
  return {d, d + n};
}

}  // namespace tactile::test
