#pragma once
// The display's HID interface as Linux presents it with the kernel's usbhid driver bound: a
// hidraw node. umockdev's testbed holds the sysfs chain hidapi's hidraw back end walks (USB
// device -> interface 1 -> HID device with HID_ID/HID_NAME/HID_UNIQ and its binary
// report_descriptor -> hidraw0 with DEVNAME=/dev/hidraw0), and this class answers the node's
// ioctls, reads and writes as the kernel would, with the real firmware (fake_firmware.hpp)
// behind them:
// - HIDIOCGRDESCSIZE, HIDIOCGRDESC, HIDIOCGRAWINFO from the firmware's descriptors;
// - HIDIOCGFEATURE / HIDIOCSFEATURE as GET_REPORT / SET_REPORT control transfers on
//   interface 1 (what usbhid sends);
// - write(): one output report, report ID first, as an interrupt OUT transfer on EP 0x02
//   that waits while the firmware NAKs it (FIFO full), as usb_interrupt_msg() does, up to the
//   kernel's 5 s USB_CTRL_SET_TIMEOUT;
// - after unplug(): every call fails with ENODEV, as hidraw does once its device is gone.
// The test binary must run under umockdev-wrapper.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tactile::test {

class FakeHidraw {
 public:
  FakeHidraw();
  ~FakeHidraw();
  FakeHidraw(const FakeHidraw&) = delete;
  FakeHidraw& operator=(const FakeHidraw&) = delete;

  static constexpr const char* kDevnode = "/dev/hidraw0";

  // Every write() the node received, as bytes (output reports, report ID first).
  std::vector<std::vector<std::uint8_t>> output_reports() const;
  // The firmware's outputs as of the host's last touch of the device (wire units).
  std::vector<std::int16_t> outputs() const;
  // Pulls the plug: calls in progress and later ones fail with ENODEV, the sysfs entries go
  // (umockdev_testbed_remove_device) and the testbed reports the removal. Thread-safe.
  void unplug();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tactile::test
