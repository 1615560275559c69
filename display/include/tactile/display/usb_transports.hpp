#pragma once
// tactile::display_usb, the one display library that links libusb and hidapi.
// Transports to a display on USB (docs/protocol.md, "USB"): libusb on the vendor interface
// (bulk OUT frames, asynchronous transfers) and hidapi on the HID interface (hidraw). Both
// check every reply and turn every USB failure, an unplugged device included, into a
// TransportError. libusb bounds every call by `timeout`; a hidraw write has no timeout of its
// own and is bounded by the kernel's 5 s transfer timeout instead (an unplug ends it at once).

#include <chrono>
#include <memory>
#include <vector>

#include "tactile/display/devices.hpp"
#include "tactile/display/transport.hpp"

namespace tactile::display {

struct PlayBackends;  // play_anywhere.hpp

// Lists every attached device with the project's vendor/product ID, through libusb and
// through hidapi (a display exposing both interfaces appears once per back end). Returns an
// empty list when none is attached or when the system has no USB at all.
std::vector<DeviceDescription> list_usb_devices();

// play_anywhere's displays on USB: list_usb_devices and open_usb_transport.
PlayBackends usb_play_backends();

struct UsbTransportOptions {
  // Longest any USB operation may take before it is reported as failed.
  std::chrono::milliseconds timeout{1000};
  // Frames queued in the host controller at once (libusb); more hides host scheduling gaps,
  // the device's FIFO does the rest.
  int frames_in_flight = 4;
};

// Opens `device` (as listed by list_usb_devices()) through its back end ("libusb" or
// "hidapi") and reads its device information. Throws TransportError naming the device.
std::unique_ptr<Transport> open_usb_transport(const DeviceDescription& device,
                                              const UsbTransportOptions& options = {});

std::unique_ptr<Transport> open_libusb_transport(const DeviceDescription& device,
                                                 const UsbTransportOptions& options = {});
std::unique_ptr<Transport> open_hidapi_transport(const DeviceDescription& device,
                                                 const UsbTransportOptions& options = {});

}  // namespace tactile::display
