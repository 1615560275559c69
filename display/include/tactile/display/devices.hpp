#pragma once
// Attached displays on USB as plain data, which the playback plan chooses from; listing them
// (list_usb_devices) is tactile::display_usb's, in usb_transports.hpp.
//
// USB identity: vendor 0x1209 (pid.codes, the open-source hardware vendor ID) with product
// 0x0001, the pid.codes *test* PID, until the project is allocated a PID of its own.

#include <cstdint>
#include <string>
#include <vector>

#include "tactile/display/transport.hpp"

namespace tactile::display {

inline constexpr std::uint16_t kUsbVendorId = 0x1209;
inline constexpr std::uint16_t kUsbProductId = 0x0001;

struct DeviceDescription {
  Backend backend = Backend::libusb;  // libusb (vendor interface) or hidapi (HID interface)
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::uint8_t bus = 0;       // libusb only
  std::uint8_t address = 0;   // libusb only
  std::string path;           // hidapi device path (/dev/hidrawN), or "bus:address" for libusb
  int interface_number = -1;  // hidapi: the USB interface of the HID device (1 on a display)
  std::string manufacturer;   // empty when the device could not be opened to read strings
  std::string product;
  std::string serial;
  bool accessible = false;  // false: found but not openable (permissions: see the udev rules)
};

}  // namespace tactile::display
