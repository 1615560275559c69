#pragma once
// A display on a fake USB bus: umockdev's testbed provides the sysfs entry and the usbdevfs
// node /dev/bus/usb/001/002 (port 1 of bus 1), and this class answers the node's ioctls (URBs) with
// the real firmware (fake_firmware.hpp). libusb in the test process then talks to it exactly as
// to hardware. The test binary must run under umockdev-wrapper (LD_PRELOAD of
// libumockdev-preload). The HID interface as Linux presents it (hidraw) is fake_hidraw.hpp.
//
// The device's playout clock is real time, advanced lazily whenever the host touches the
// device (each ioctl), which is how a host observes a device anyway.

#include <cstdint>
#include <memory>
#include <vector>

namespace tactile::test {

class FakeDisplay {
 public:
  FakeDisplay();
  ~FakeDisplay();
  FakeDisplay(const FakeDisplay&) = delete;
  FakeDisplay& operator=(const FakeDisplay&) = delete;

  // Every bulk transfer received on EP 0x01, as the bytes that came over the wire.
  std::vector<std::vector<std::uint8_t>> bulk_transfers() const;
  // The firmware's outputs as of the host's last touch of the device (wire units).
  std::vector<std::int16_t> outputs() const;
  // Pulls the plug: transfers in flight end with ENODEV, new ones are refused, and the
  // testbed reports the removal.
  void unplug();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tactile::test
