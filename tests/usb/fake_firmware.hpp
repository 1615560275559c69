#pragma once
// The real firmware (tfw_device + tfw_usb, full speed, the STReSS-like test configuration)
// behind a fake device controller: what the fake displays on umockdev's buses put behind their
// device nodes. Not thread-safe; the fakes hold their own lock around it.

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "tactile_fw/usb.h"

namespace tactile::test {

class FakeFirmware {
 public:
  explicit FakeFirmware(const char* serial);
  FakeFirmware(const FakeFirmware&) = delete;  // the device controller points at this object
  FakeFirmware& operator=(const FakeFirmware&) = delete;

  // One control transfer: `setup` with its data stage in `data` (IN: filled with the reply,
  // at most wLength bytes). Returns the bytes transferred, or -1 when the device stalled.
  int control(const std::uint8_t setup[8], std::uint8_t* data);

  // Plays the ticks that real time says have passed since the last look (at most 100 per
  // look, so a slow host sees underruns rather than a stall).
  void advance();

  // The firmware's outputs as it last wrote them (wire units, 0.1 um), one per contactor.
  std::vector<std::int16_t> outputs() const;

  // Whether OUT endpoint `ep` (1 bulk, 2 HID) would take a packet now, or NAK it.
  bool out_ready(std::uint8_t ep) const { return ready_[ep & 3]; }
  // The latest HID input report offered by the firmware (cleared when taken).
  std::vector<std::uint8_t> take_hid_in();

  // Device and configuration descriptors as one hex string (sysfs `descriptors`).
  std::string descriptors_hex();
  // The HID report descriptor.
  std::vector<std::uint8_t> hid_report_descriptor();

  tfw_usb usb{};

 private:
  static int dcd_write(void* context, std::uint8_t ep, const std::uint8_t* data, std::uint16_t len);
  static void dcd_stall(void* context, std::uint8_t ep);
  static void dcd_ready(void* context, std::uint8_t ep, int ready);

  tfw_device dev_{};
  bool ready_[3] = {true, true, true};  // OUT endpoints, by number
  std::vector<std::uint8_t> ep0_reply_;
  bool ep0_stalled_ = false;
  std::vector<std::uint8_t> hid_in_;
  std::chrono::steady_clock::time_point last_tick_ = std::chrono::steady_clock::now();
};

}  // namespace tactile::test
